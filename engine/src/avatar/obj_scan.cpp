#include "avatar/obj_scan.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace drape::detail {
namespace {

// Calls visit(lineNumber, keyword, restOfLine) for each line; stops when visit returns true.
template <typename Visit>
void forEachObjLine(const std::filesystem::path& file, Visit visit) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  int lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword)) continue;
    std::string rest;
    std::getline(words, rest);
    if (visit(lineNumber, keyword, rest)) return;
  }
}

}  // namespace

ObjProblem findNonFiniteObjVertex(const std::filesystem::path& file) {
  ObjProblem problem;
  int vertex = 0;
  forEachObjLine(file, [&](int lineNumber, const std::string& keyword, const std::string& rest) {
    if (keyword != "v") return false;
    ++vertex;
    std::istringstream words(rest);
    std::string text[3];
    double value[3];
    bool finite = true;
    for (int k = 0; k < 3; ++k) {
      words >> text[k];
      char* end = nullptr;
      value[k] = std::strtod(text[k].c_str(), &end);
      finite = finite && !text[k].empty() && std::isfinite(value[k]);
    }
    if (finite) return false;
    problem = {true, lineNumber,
               "vertex " + std::to_string(vertex) + ": non-finite coordinate (" + text[0] + ", " + text[1] + ", " +
                   text[2] + ")"};
    return true;
  });
  return problem;
}

ObjProblem findBadObjFaceIndex(const std::filesystem::path& file) {
  long totalVertices = 0;
  forEachObjLine(file, [&](int, const std::string& keyword, const std::string&) {
    totalVertices += keyword == "v" ? 1 : 0;
    return false;
  });
  ObjProblem problem;
  long verticesSoFar = 0;
  int face = 0;
  forEachObjLine(file, [&](int lineNumber, const std::string& keyword, const std::string& rest) {
    if (keyword == "v") {
      ++verticesSoFar;
      return false;
    }
    if (keyword != "f") return false;
    ++face;
    std::istringstream words(rest);
    std::string corner;
    while (words >> corner) {
      // "i", "i/t", "i//n", "i/t/n": the position index comes first; a negative one counts back from the last
      // vertex defined so far, a positive one may refer to any vertex of the file.
      const long index = std::strtol(corner.c_str(), nullptr, 10);
      const bool valid = index < 0 ? verticesSoFar + index >= 0 : (index >= 1 && index <= totalVertices);
      if (valid) continue;
      problem = {true, lineNumber,
                 "face " + std::to_string(face) + " refers to vertex " + std::to_string(index) + " (file has " +
                     std::to_string(totalVertices) + " vertices)"};
      return true;
    }
    return false;
  });
  return problem;
}

ObjProblem findLargeObjFace(const std::filesystem::path& file, unsigned maxCorners) {
  ObjProblem problem;
  int face = 0;
  forEachObjLine(file, [&](int lineNumber, const std::string& keyword, const std::string& rest) {
    if (keyword != "f") return false;
    ++face;
    std::istringstream words(rest);
    std::string corner;
    unsigned corners = 0;
    while (words >> corner) ++corners;
    if (corners <= maxCorners) return false;
    problem = {true, lineNumber, "face " + std::to_string(face) + " with " + std::to_string(corners) + " vertices"};
    return true;
  });
  return problem;
}

}  // namespace drape::detail
