#pragma once
// A garment state read back from an OBJ that exportGarment wrote (drape --simulate -o OUT.obj): the vertex
// positions of the same garment, in its vertex order, so that a stage can start from them (drape --from).
// Only OBJ: the other export formats go through assimp, which splits vertices along UV seams and reorders them.
#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "drape/garment/garment.h"

namespace drape {

struct GarmentState {
  Eigen::MatrixX3d positions;  // |V| x 3, metres, in the file's vertex order
  Eigen::MatrixX3i faces;      // |F| x 3, 0-based vertex indices; no rows when the file has no faces
  std::vector<int> faceLines;  // |F|, the file's line number of each face
};

// Reads the "v" and "f" lines of an OBJ (other lines are skipped; a "v" line's extra numbers, e.g. colours, are
// ignored; "f a/b/c" takes a; negative indices count back from the last vertex). Throws InputError naming the
// file, and the line where one is at fault: a file that cannot be read, not .obj, a vertex without three finite
// numbers, a face that is not a triangle or names a vertex that does not exist, no vertices.
GarmentState readGarmentState(const std::filesystem::path& file);

// Checks that state belongs to garment: the same vertex count and, when it has faces, the same triangles (each
// face one of garment.triangles with the same orientation, every triangle once), so that a file written from
// another scene, another mesh setting, or reordered by another tool is refused instead of simulated wrongly.
// Throws InputError naming the file and the first difference.
void checkGarmentState(const GarmentState& state, const Garment& garment, const std::filesystem::path& file);

// readGarmentState then checkGarmentState: the positions (|V| x 3, metres) of garment stored in file.
Eigen::MatrixX3d readGarmentPositions(const std::filesystem::path& file, const Garment& garment);

}  // namespace drape
