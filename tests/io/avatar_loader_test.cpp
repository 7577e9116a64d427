// loadAvatar on small files in every supported format, on malformed ones (tests/data/avatars), and on the
// GarmentCode body in ../shared/data.
#include "drape/avatar/avatar_loader.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>
#include <string>

#include "drape/collision/avatar_collider.h"
#include "drape/core/input_error.h"
#include "drape/geometry/primitives.h"
#include "shared_data.h"

namespace drape {
namespace {

std::filesystem::path avatarFile(const std::string& name) { return test::testDataDir() / "avatars" / name; }

// The message of the InputError thrown by loadAvatar, or "" when it does not throw.
std::string loadError(const std::filesystem::path& file, Diagnostics* diagnostics = nullptr) {
  try {
    loadAvatar(file, 1.0, diagnostics);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expectCube(const TriangleMesh& mesh, const Eigen::Vector3d& lo, double side) {
  EXPECT_EQ(mesh.vertexCount(), 8);
  EXPECT_EQ(mesh.triangleCount(), 12);
  EXPECT_TRUE(isClosedManifold(mesh));
  EXPECT_NEAR(signedVolume(mesh), side * side * side, 1e-9);  // positive: still outward after loading
  const BoundingBox bounds = boundsOf(mesh.vertices);
  EXPECT_TRUE(bounds.min.isApprox(lo, 1e-9)) << bounds.min.transpose();
  EXPECT_TRUE(bounds.max.isApprox(lo + Eigen::Vector3d::Constant(side), 1e-9)) << bounds.max.transpose();
}

TEST(AvatarLoaderTest, LoadsCubeInEveryFormat) {
  for (const char* name : {"cube.obj", "cube.ply", "cube.stl"}) {
    SCOPED_TRACE(name);
    Diagnostics diagnostics;
    expectCube(loadAvatar(avatarFile(name), 1.0, &diagnostics), Eigen::Vector3d::Zero(), 0.5);
    EXPECT_TRUE(diagnostics.warnings().empty());
  }
}

TEST(AvatarLoaderTest, AppliesNestedNodeTransformsOfGltf) {
  // root: translate (0,1,0), scale 2; child: translate (1,0,0); mesh [0,0.5]^3 -> [2,3] x [1,2] x [0,1].
  expectCube(loadAvatar(avatarFile("cube_nested_nodes.gltf")), Eigen::Vector3d(2.0, 1.0, 0.0), 1.0);
}

TEST(AvatarLoaderTest, ScalesByUnitsInMeter) {
  const TriangleMesh metres = loadAvatar(avatarFile("cube.obj"));
  const TriangleMesh scaled = loadAvatar(avatarFile("cube.obj"), unitsInMeterFromName("cm"));
  ASSERT_EQ(scaled.vertexCount(), metres.vertexCount());
  EXPECT_TRUE(scaled.vertices.isApprox(metres.vertices / 100.0));
  EXPECT_THROW(loadAvatar(avatarFile("cube.obj"), 0.0), InputError);
  EXPECT_THROW(loadAvatar(avatarFile("cube.obj"), -1.0), InputError);
}

TEST(AvatarLoaderTest, MissingFileIsNamed) {
  const auto file = avatarFile("nonexistent.obj");
  EXPECT_EQ(loadError(file), file.string() + ": file not found");
  EXPECT_EQ(loadError(test::testDataDir() / "avatars"),
            (test::testDataDir() / "avatars").string() + ": not a regular file");
}

TEST(AvatarLoaderTest, EmptyObjHasNoTriangles) {
  const auto file = avatarFile("empty.obj");
  EXPECT_EQ(loadError(file), file.string() + ": contains no triangles");
}

TEST(AvatarLoaderTest, GarbageFilesAreRejected) {
  // assimp's OBJ reader skips lines it does not understand, so random bytes in a .obj give no triangles.
  const auto obj = avatarFile("garbage.obj");
  EXPECT_EQ(loadError(obj), obj.string() + ": contains no triangles");
  // For .glb no reader accepts the bytes; assimp's reason is passed on.
  const auto glb = avatarFile("garbage.glb");
  const std::string message = loadError(glb);
  EXPECT_EQ(message.rfind(glb.string() + ": cannot read mesh: ", 0), 0u) << message;
  EXPECT_NE(message.find("No suitable reader"), std::string::npos) << message;
}

TEST(AvatarLoaderTest, NonFiniteCoordinateNamesVertexAndLine) {
  const auto file = avatarFile("nan_vertex.obj");
  EXPECT_EQ(loadError(file), file.string() + ": line 7: vertex 6: non-finite coordinate (0.5, nan, 0.5)");
}

TEST(AvatarLoaderTest, FaceIndexOutOfRangeNamesFaceAndLine) {
  const auto file = avatarFile("face_index_out_of_range.obj");
  EXPECT_EQ(loadError(file), file.string() + ": line 13: face 4 refers to vertex 9 (file has 8 vertices)");
}

TEST(AvatarLoaderTest, DegenerateFacesAreDroppedWithOneWarning) {
  const auto file = avatarFile("degenerate_faces.obj");
  Diagnostics diagnostics;
  const TriangleMesh mesh = loadAvatar(file, 1.0, &diagnostics);
  expectCube(mesh, Eigen::Vector3d::Zero(), 0.5);  // the collinear face's extra vertex is gone as well
  ASSERT_EQ(diagnostics.warnings().size(), 1u);
  EXPECT_EQ(diagnostics.warnings()[0],
            file.string() + ": dropped 3 degenerate faces (zero area or repeated vertex) of 15");
  // Without a Diagnostics the same mesh comes out and nothing throws.
  EXPECT_EQ(loadAvatar(file).triangleCount(), 12);
}

TEST(AvatarLoaderTest, OnlyDegenerateFacesIsAnError) {
  const auto file = test::testOutputDir() / "avatar_only_degenerate.obj";
  std::ofstream(file) << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n";
  EXPECT_EQ(loadError(file), file.string() + ": contains no triangles with a non-zero area");
}

TEST(AvatarLoaderTest, MeshesOfSeveralObjectsAreMergedAndWelded) {
  // Two OBJ objects with different materials share the cube's vertices: assimp keeps two meshes; the loader
  // merges them and welds the shared positions, so the result is the closed cube again.
  const auto file = test::testOutputDir() / "avatar_two_objects.obj";
  const auto mtl = test::testOutputDir() / "avatar_two_objects.mtl";
  std::ofstream(mtl) << "newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\n";
  std::ofstream out(file);
  out << "mtllib avatar_two_objects.mtl\n";
  for (int i = 0; i < 8; ++i)
    out << "v " << (i & 1 ? 0.5 : 0) << " " << (i & 2 ? 0.5 : 0) << " " << (i & 4 ? 0.5 : 0) << "\n";
  out << "o bottom\nusemtl a\nf 1 3 2\nf 2 3 4\nf 5 6 7\nf 6 8 7\nf 1 2 5\nf 2 6 5\n";
  out << "o top\nusemtl b\nf 3 7 4\nf 4 7 8\nf 1 5 3\nf 3 5 7\nf 2 4 6\nf 4 8 6\n";
  out.close();
  expectCube(loadAvatar(file), Eigen::Vector3d::Zero(), 0.5);
}

// The cube of avatar_two_objects.obj as OBJ text: its eight vertices (moved by offset), and its faces numbered from
// base + 1, those listed in `flipped` (0-based) wound the other way.
std::string cubeVertices(const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
  std::ostringstream out;
  for (int i = 0; i < 8; ++i)
    out << "v " << offset.x() + (i & 1 ? 0.5 : 0) << " " << offset.y() + (i & 2 ? 0.5 : 0) << " "
        << offset.z() + (i & 4 ? 0.5 : 0) << "\n";
  return out.str();
}

std::string cubeFaces(const std::vector<int>& flipped, int base = 0) {
  const int faces[12][3] = {{1, 3, 2}, {2, 3, 4}, {5, 6, 7}, {6, 8, 7}, {1, 2, 5}, {2, 6, 5},
                            {3, 7, 4}, {4, 7, 8}, {1, 5, 3}, {3, 5, 7}, {2, 4, 6}, {4, 8, 6}};
  std::ostringstream out;
  for (int f = 0; f < 12; ++f) {
    const bool turn = std::find(flipped.begin(), flipped.end(), f) != flipped.end();
    out << "f " << base + faces[f][0] << " " << base + faces[f][turn ? 2 : 1] << " " << base + faces[f][turn ? 1 : 2]
        << "\n";
  }
  return out.str();
}

std::filesystem::path writeObj(const std::string& name, const std::string& text) {
  const auto file = test::testOutputDir() / name;
  std::ofstream(file) << text;
  return file;
}

// Bodies exported inside out (a mirroring transform) or with single faces flipped come out wound outward, with one
// warning; the collider takes the inside of the body from the winding.
TEST(AvatarLoaderTest, InsideOutCubeIsTurnedOutward) {
  std::vector<int> all(12);
  for (int f = 0; f < 12; ++f) all[f] = f;
  const auto file = writeObj("avatar_inside_out.obj", cubeVertices() + cubeFaces(all));
  Diagnostics diagnostics;
  expectCube(loadAvatar(file, 1.0, &diagnostics), Eigen::Vector3d::Zero(), 0.5);
  ASSERT_EQ(diagnostics.warnings().size(), 1u);
  EXPECT_EQ(diagnostics.warnings()[0],
            file.string() + ": 12 of 12 faces were wound inward and are turned outward (1 part was inside out)");
}

TEST(AvatarLoaderTest, SingleFlippedFacesAreTurnedToMatchTheirNeighbours) {
  // Face 0 is the one the search starts from: the part is first made to agree with it, then turned over.
  for (const std::vector<int>& flipped : {std::vector<int>{0}, std::vector<int>{5}, std::vector<int>{2, 9}}) {
    SCOPED_TRACE(::testing::PrintToString(flipped));
    const auto file = writeObj("avatar_flipped_faces.obj", cubeVertices() + cubeFaces(flipped));
    Diagnostics diagnostics;
    expectCube(loadAvatar(file, 1.0, &diagnostics), Eigen::Vector3d::Zero(), 0.5);
    ASSERT_EQ(diagnostics.warnings().size(), 1u);
    EXPECT_EQ(diagnostics.warnings()[0], file.string() + ": " + std::to_string(flipped.size()) +
                                             " of 12 faces were wound inward and are turned outward");
  }
}

TEST(AvatarLoaderTest, EachPartIsTurnedOnItsOwnAndSheetsKeepTheirWinding) {
  std::vector<int> all(12);
  for (int f = 0; f < 12; ++f) all[f] = f;
  // An outward cube, an inside-out cube 1 m away, and a square sheet (encloses nothing) wound either way.
  for (const char* sheet : {"f 17 18 19\nf 17 19 20\n", "f 17 19 18\nf 17 20 19\n"}) {
    SCOPED_TRACE(sheet);
    const std::string text = cubeVertices() + cubeVertices(Eigen::Vector3d(1.0, 0.0, 0.0)) +
                             "v 0 -1 0\nv 1 -1 0\nv 1 -1 1\nv 0 -1 1\n" + cubeFaces({}) + cubeFaces(all, 8) + sheet;
    const auto file = writeObj("avatar_two_cubes_and_sheet.obj", text);
    Diagnostics diagnostics;
    const TriangleMesh mesh = loadAvatar(file, 1.0, &diagnostics);
    ASSERT_EQ(mesh.triangleCount(), 26);
    TriangleMesh first, second;
    first.vertices = second.vertices = mesh.vertices;
    first.triangles = mesh.triangles.topRows(12);
    second.triangles = mesh.triangles.middleRows(12, 12);
    EXPECT_NEAR(signedVolume(first), 0.125, 1e-9);
    EXPECT_NEAR(signedVolume(second), 0.125, 1e-9);
    // The sheet's triangles are the file's last two (the loader keeps the face order).
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(24, 0)).transpose();
    const Eigen::Vector3d n = (mesh.vertices.row(mesh.triangles(24, 1)).transpose() - a)
                                  .cross(mesh.vertices.row(mesh.triangles(24, 2)).transpose() - a);
    EXPECT_NEAR(std::abs(n.y()), 1.0, 1e-12);
    EXPECT_EQ(n.y() > 0.0, std::string(sheet).rfind("f 17 19 18", 0) == 0) << "the sheet keeps its winding";
    ASSERT_EQ(diagnostics.warnings().size(), 1u);
    EXPECT_EQ(diagnostics.warnings()[0],
              file.string() + ": 12 of 26 faces were wound inward and are turned outward (1 part was inside out)");
  }
}

// The library mannequin written inside out (every face reversed, as a mirroring export leaves it) loads as the same
// body: the collider's signed distances agree everywhere. Before, the whole outside counted as inside the body and a
// drape of the default t-shirt on it pulled the shirt into the torso (mean |z| 3.3 cm against 6.9 cm at 0.3 s).
TEST(AvatarLoaderTest, InsideOutMannequinGivesTheSameSignedDistances) {
  const auto original = test::assetsDir() / "avatars" / "female.obj";
  std::ifstream in(original);
  std::ostringstream flipped;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("f ", 0) == 0) {
      std::istringstream corners(line.substr(2));
      std::vector<std::string> c{std::istream_iterator<std::string>(corners), std::istream_iterator<std::string>()};
      ASSERT_EQ(c.size(), 3u) << line;
      flipped << "f " << c[0] << " " << c[2] << " " << c[1] << "\n";
    } else {
      flipped << line << "\n";
    }
  }
  const auto file = writeObj("avatar_female_inside_out.obj", flipped.str());
  Diagnostics diagnostics;
  const collision::AvatarCollider turned(loadAvatar(file, 1.0, &diagnostics));
  const collision::AvatarCollider body(loadAvatar(original));
  ASSERT_EQ(diagnostics.warnings().size(), 1u);
  EXPECT_NE(diagnostics.warnings()[0].find("(1 part was inside out)"), std::string::npos) << diagnostics.warnings()[0];
  int inside = 0;
  for (int i = 0; i < 400; ++i) {  // points on a grid through the torso and around it
    const Eigen::Vector3d p(-0.3 + 0.6 * (i % 7) / 6.0, 0.9 + 0.6 * ((i / 7) % 8) / 7.0, -0.2 + 0.4 * (i / 56) / 7.0);
    const double d = body.signedDistance(p);
    EXPECT_NEAR(turned.signedDistance(p), d, 1e-12) << p.transpose();
    inside += d < 0.0;
  }
  EXPECT_GT(inside, 20) << "some points lie inside the body";
  EXPECT_LT(inside, 380) << "some lie outside";
}

TEST(AvatarLoaderTest, GarmentCodeMeanBody) {
  DRAPE_SHARED_FILE(file, "garmentcode/mean_all.obj");
  Diagnostics diagnostics;
  const TriangleMesh body = loadAvatar(file, unitsInMeterFromName("m"), &diagnostics);
  // The file has 23,752 vertices and 47,500 triangles (closed, genus 0: F = 2V - 4), but vertices 10753 and
  // 10770 (1-based, at the mouth: the lips touch) have identical coordinates. assimp's OBJ reader keeps no
  // indices; JoinIdenticalVertices rebuilds them by position and merges that pair, so 23,751 come out. Every
  // edge is still shared by exactly two triangles (the pair is not adjacent): the surface is pinched at one point.
  EXPECT_EQ(body.vertexCount(), 23752 - 1);
  EXPECT_EQ(body.triangleCount(), 2 * 23752 - 4);
  EXPECT_TRUE(diagnostics.warnings().empty());
  const BoundingBox bounds = boundsOf(body.vertices);
  EXPECT_NEAR(bounds.size().y(), 1.72, 0.02);
  EXPECT_NEAR(bounds.min.y(), 0.0, 0.01);
  EXPECT_TRUE(isClosedManifold(body));
  EXPECT_GT(signedVolume(body), 0.04);  // outward; an adult body is some 0.05-0.1 m^3
  EXPECT_LT(signedVolume(body), 0.12);
}

}  // namespace
}  // namespace drape
