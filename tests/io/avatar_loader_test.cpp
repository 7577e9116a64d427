// loadAvatar on small files in every supported format, on malformed ones (tests/data/avatars), and on the
// GarmentCode body in ../shared/data.
#include "drape/avatar/avatar_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

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

TEST(AvatarLoaderTest, UnitNames) {
  EXPECT_EQ(unitsInMeterFromName("m"), 1.0);
  EXPECT_EQ(unitsInMeterFromName("cm"), 100.0);
  EXPECT_EQ(unitsInMeterFromName("mm"), 1000.0);
  try {
    unitsInMeterFromName("inch");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "unknown length unit 'inch' (valid: m, cm, mm)");
  }
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
