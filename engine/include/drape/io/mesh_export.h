#pragma once
// Export of a garment (placed or draped) and of plain meshes. OBJ carries UVs from the pattern coordinates
// and one group per panel; .glb/.gltf go through assimp's exporter. All writes are atomic.
#include <filesystem>

#include "drape/garment/garment.h"
#include "drape/geometry/triangle_mesh.h"

namespace drape {

// Format from the extension: .obj, .glb, .gltf, .ply, .stl. positions: |V| x 3 metres (e.g. a draped state);
// pass garment.positions for the placed garment.
void exportGarment(const Garment& garment, const Eigen::MatrixX3d& positions, const std::filesystem::path& file);

void exportMesh(const TriangleMesh& mesh, const std::filesystem::path& file);

}  // namespace drape
