// A polygon with more corners than the loader accepts (docs/FORMATS.md "Limits") is refused before assimp
// triangulates it, in OBJ (naming the line) and in PLY (naming the mesh and face). The files are written here:
// a 100k-corner face is megabytes of text.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include "drape/avatar/avatar_loader.h"
#include "drape/core/input_error.h"
#include "shared_data.h"

namespace drape {
namespace {

const std::filesystem::path kScratch = test::testOutputDir() / "avatar_large_polygon";

std::string loadError(const std::filesystem::path& file) {
  try {
    loadAvatar(file, 1.0);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// A cube's 6 quads plus, after them, one flat n-gon (a circle of radius 0.5 at y = 2) as a single face.
std::filesystem::path writeObj(const std::string& name, int n) {
  std::filesystem::create_directories(kScratch);
  const std::filesystem::path file = kScratch / name;
  std::ofstream out(file);
  out.precision(9);
  out << "# cube and one " << n << "-gon\n";
  for (int i = 0; i < 8; ++i) out << "v " << (i & 1) << " " << ((i >> 1) & 1) << " " << ((i >> 2) & 1) << "\n";
  out << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    out << "v " << 0.5 * std::cos(a) << " 2 " << 0.5 * std::sin(a) << "\n";
  }
  out << "f";
  for (int k = 0; k < n; ++k) out << " " << 9 + k;
  out << "\n";
  return file;
}

std::filesystem::path writePly(const std::string& name, int n) {
  std::filesystem::create_directories(kScratch);
  const std::filesystem::path file = kScratch / name;
  std::ofstream out(file);
  out.precision(9);
  out << "ply\nformat ascii 1.0\nelement vertex " << n << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "element face 1\nproperty list uint int vertex_indices\nend_header\n";
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    out << 0.5 * std::cos(a) << " 0 " << 0.5 * std::sin(a) << "\n";
  }
  out << n;
  for (int k = 0; k < n; ++k) out << " " << k;
  out << "\n";
  return file;
}

TEST(AvatarLargePolygon, ObjFaceOfHundredThousandCornersNamesTheLine) {
  const auto file = writeObj("huge_face.obj", 100000);
  // Line: 1 comment, 8 + 100000 vertex lines and 6 quads before the big face.
  const int line = 1 + 8 + 6 + 100000 + 1;
  EXPECT_EQ(loadError(file),
            file.string() + ": line " + std::to_string(line) + ": face 7 with 100000 vertices (at most 1000)");
}

TEST(AvatarLargePolygon, ObjFaceAtTheLimitLoads) {
  const auto file = writeObj("face_at_limit.obj", 1000);
  const TriangleMesh mesh = loadAvatar(file, 1.0);
  // 12 cube triangles and n - 2 for the n-gon.
  EXPECT_EQ(mesh.triangleCount(), 12 + 998);
}

TEST(AvatarLargePolygon, PlyFaceOfHundredThousandCornersNamesTheFace) {
  const auto file = writePly("huge_face.ply", 100000);
  const std::string message = loadError(file);
  EXPECT_EQ(message.rfind(file.string() + ": mesh 0 ", 0), 0u) << message;
  EXPECT_NE(message.find("face 0 has 100000 vertices (at most 1000)"), std::string::npos) << message;
}

}  // namespace
}  // namespace drape
