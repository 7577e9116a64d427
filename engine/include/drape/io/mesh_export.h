#pragma once
// Export of a garment (placed or draped) and of plain meshes. OBJ carries UVs from the pattern coordinates
// and one group per panel; .glb/.gltf go through assimp's exporter. All writes are atomic.
#include <filesystem>

#include "drape/garment/garment.h"
#include "drape/geometry/triangle_mesh.h"

namespace drape {

// Format from the extension (case-insensitive):
//   .obj   written by Drape: v (9 significant digits), vt = garment.uvs, vn (area-weighted), "g <panel name>"
//          per panel (whitespace in names becomes '_'), faces "f v/vt/vn", 1-based;
//   .glb   binary glTF 2.0 through assimp: one mesh and node per panel, named after it, with UVs and normals;
//   .gltf  the same as text, the buffer embedded as a base64 data URI (one self-contained file);
//   .ply   binary PLY through assimp: one mesh with UVs and normals;
//   .stl   binary STL through assimp.
// positions: |V| x 3 metres (e.g. a draped state); pass garment.positions for the placed garment.
// Throws InputError naming the file for an unknown extension (listing the valid ones), a positions/garment size
// mismatch, non-finite positions, no triangles, or a failed write (the old file is then kept).
void exportGarment(const Garment& garment, const Eigen::MatrixX3d& positions, const std::filesystem::path& file);

// Same formats for a plain mesh (no UVs; one group/mesh named after the file's stem).
void exportMesh(const TriangleMesh& mesh, const std::filesystem::path& file);

}  // namespace drape
