#pragma once
// A second, plain reading of an OBJ file, used only after assimp has refused it or produced bad data, to tell
// the user where in the file the problem is (assimp's messages and vertex order do not say).
#include <filesystem>
#include <string>

namespace drape::detail {

struct ObjProblem {
  bool found = false;
  int line = 0;         // 1-based line number in the file
  std::string message;  // e.g. "vertex 6: non-finite coordinate (0.5, nan, 0.5)" (OBJ's 1-based numbering)
};

// The first vertex line ("v x y z") with a coordinate that is not a finite number.
ObjProblem findNonFiniteObjVertex(const std::filesystem::path& file);

// The first face ("f ...") with a vertex reference that is 0 or out of range (negative ones resolved as in OBJ).
ObjProblem findBadObjFaceIndex(const std::filesystem::path& file);

// The first face ("f ...") with more than maxCorners corners: "face F with N vertices".
ObjProblem findLargeObjFace(const std::filesystem::path& file, unsigned maxCorners);

}  // namespace drape::detail
