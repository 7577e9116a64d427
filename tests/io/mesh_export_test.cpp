// Export round trips: a hand-built two-panel garment to OBJ/glTF/GLB/PLY/STL, read back with loadAvatar and
// with assimp directly; positions, triangles (with orientation), panel groups and UVs are compared.
#include "drape/io/mesh_export.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <fstream>
#include <set>
#include <sstream>

#include "drape/avatar/avatar_loader.h"
#include "drape/core/input_error.h"
#include "drape/geometry/primitives.h"
#include "shared_data.h"

namespace drape {
namespace {

// Two square panels, two triangles each, 0.5 m apart along x; UVs = rest coordinates laid side by side.
Garment twoPanelGarment() {
  Garment g;
  g.panelNames = {"front", "back panel"};
  g.rest.resize(8, 2);
  g.rest << 0, 0, 0.4, 0, 0.4, 0.6, 0, 0.6,  //
      0, 0, 0.4, 0, 0.4, 0.6, 0, 0.6;
  g.uvs = g.rest;
  g.uvs.bottomRows(4).col(0).array() += 0.5;
  g.positions.resize(8, 3);
  g.positions << 0, 1, 0.1, 0.4, 1, 0.1, 0.4, 1.6, 0.1, 0, 1.6, 0.1,  // front, facing +z
      0.4, 1, -0.1, 0, 1, -0.1, 0, 1.6, -0.1, 0.4, 1.6, -0.1;         // back, facing -z
  g.triangles.resize(4, 3);
  g.triangles << 0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7;
  g.trianglePanel.resize(4);
  g.trianglePanel << 0, 0, 1, 1;
  g.vertexPanel.resize(8);
  g.vertexPanel << 0, 0, 0, 0, 1, 1, 1, 1;
  return g;
}

// Index of the row of `points` within tolerance of p, or -1.
int findPoint(const Eigen::MatrixX3d& points, const Eigen::Vector3d& p, double tolerance) {
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if ((points.row(i).transpose() - p).norm() <= tolerance) return static_cast<int>(i);
  }
  return -1;
}

// Triangles as sets of cyclically normalised index triples (smallest index first, orientation kept).
std::set<std::array<int, 3>> triangleSet(const Eigen::MatrixX3i& t, const std::vector<int>& map = {}) {
  std::set<std::array<int, 3>> result;
  for (Eigen::Index f = 0; f < t.rows(); ++f) {
    std::array<int, 3> a{};
    for (int k = 0; k < 3; ++k) a[k] = map.empty() ? t(f, k) : map[t(f, k)];
    std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
    result.insert(a);
  }
  return result;
}

// Same positions (order-independent, within tolerance) and same oriented triangles.
void expectSameMesh(const TriangleMesh& loaded, const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& triangles,
                    double tolerance) {
  ASSERT_EQ(loaded.vertexCount(), positions.rows());
  ASSERT_EQ(loaded.triangleCount(), triangles.rows());
  std::vector<int> toOriginal(static_cast<std::size_t>(loaded.vertexCount()));
  for (int i = 0; i < loaded.vertexCount(); ++i) {
    toOriginal[i] = findPoint(positions, loaded.vertices.row(i).transpose(), tolerance);
    ASSERT_GE(toOriginal[i], 0) << "loaded vertex " << i << " (" << loaded.vertices.row(i) << ") not exported";
  }
  EXPECT_EQ(triangleSet(loaded.triangles, toOriginal), triangleSet(triangles));
}

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool hasTemporaryFiles(const std::filesystem::path& directory) {
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) return true;
  }
  return false;
}

std::filesystem::path freshDir(const std::string& name) {
  const auto dir = test::testOutputDir() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(MeshExportTest, GarmentObjHasGroupsUvsAndRoundTrips) {
  const Garment g = twoPanelGarment();
  const auto dir = freshDir("export_obj");
  const auto file = dir / "garment.obj";
  exportGarment(g, g.positions, file);

  // assimp reads in single precision: ~1e-7 m.
  expectSameMesh(loadAvatar(file), g.positions, g.triangles, 1e-6);

  // The text itself: 8 v at full precision, 8 vt with the UVs, 8 vn, one group per panel (spaces replaced), v/vt/vn
  // faces.
  std::istringstream text(readText(file));
  std::string line;
  std::vector<std::string> groups;
  std::vector<Eigen::Vector2d> uvs;
  int v = 0, vn = 0, faces = 0;
  Eigen::MatrixX3d written = Eigen::MatrixX3d::Zero(8, 3);
  while (std::getline(text, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "v" && v < 8) {
      words >> written(v, 0) >> written(v, 1) >> written(v, 2);
      ++v;
    }
    if (key == "vn") ++vn;
    if (key == "vt") {
      Eigen::Vector2d uv;
      words >> uv.x() >> uv.y();
      uvs.push_back(uv);
    }
    if (key == "g") {
      std::string name;
      words >> name;
      groups.push_back(name);
    }
    if (key == "f") {
      ++faces;
      std::string corner;
      while (words >> corner) {
        const int a = std::stoi(corner);
        EXPECT_EQ(corner, std::to_string(a) + "/" + std::to_string(a) + "/" + std::to_string(a));
      }
    }
  }
  EXPECT_EQ(v, 8);
  EXPECT_LT((written - g.positions).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(vn, 8);
  EXPECT_EQ(faces, 4);
  EXPECT_EQ(groups, (std::vector<std::string>{"front", "back_panel"}));
  ASSERT_EQ(uvs.size(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_TRUE(uvs[i].isApprox(g.uvs.row(i).transpose())) << "vt " << i;
  EXPECT_FALSE(hasTemporaryFiles(dir));
}

TEST(MeshExportTest, GarmentExportUsesGivenPositions) {
  const Garment g = twoPanelGarment();
  Eigen::MatrixX3d draped = g.positions;
  draped.col(1).array() -= 0.25;  // a "draped" state differs from the placement
  const auto file = freshDir("export_draped") / "draped.obj";
  exportGarment(g, draped, file);
  expectSameMesh(loadAvatar(file), draped, g.triangles, 1e-6);
}

// glTF stores floats: positions come back to ~1e-7 m.
void expectGltfRoundTrip(const std::filesystem::path& file, const Garment& g) {
  expectSameMesh(loadAvatar(file), g.positions, g.triangles, 1e-6);

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(file.string(), aiProcess_Triangulate);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 2u);  // one per panel
  std::set<std::string> names;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    names.insert(mesh->mName.C_Str());
    EXPECT_EQ(mesh->mNumFaces, 2u);
    ASSERT_TRUE(mesh->HasTextureCoords(0));
    ASSERT_TRUE(mesh->HasNormals());
    for (unsigned i = 0; i < mesh->mNumVertices; ++i) {
      const aiVector3D& p = mesh->mVertices[i];
      const int original = findPoint(g.positions, Eigen::Vector3d(p.x, p.y, p.z), 1e-6);
      ASSERT_GE(original, 0);
      EXPECT_EQ(g.vertexPanel[original], m == 0 ? 0 : 1);
      const aiVector3D& uv = mesh->mTextureCoords[0][i];
      EXPECT_NEAR(uv.x, g.uvs(original, 0), 1e-6) << "vertex " << original;
      EXPECT_NEAR(uv.y, g.uvs(original, 1), 1e-6) << "vertex " << original;
      // Front faces +z, back faces -z.
      EXPECT_NEAR(mesh->mNormals[i].z, m == 0 ? 1.0 : -1.0, 1e-6);
    }
  }
  EXPECT_EQ(names, (std::set<std::string>{"front", "back panel"}));
}

TEST(MeshExportTest, GarmentGlbRoundTrips) {
  const Garment g = twoPanelGarment();
  const auto dir = freshDir("export_glb");
  exportGarment(g, g.positions, dir / "garment.glb");
  EXPECT_EQ(readText(dir / "garment.glb").substr(0, 4), "glTF");  // binary container magic
  expectGltfRoundTrip(dir / "garment.glb", g);
  EXPECT_FALSE(hasTemporaryFiles(dir));
}

TEST(MeshExportTest, GarmentGltfIsOneSelfContainedFile) {
  const Garment g = twoPanelGarment();
  const auto dir = freshDir("export_gltf");
  exportGarment(g, g.positions, dir / "garment.gltf");
  // The buffer is embedded as a data URI: the directory holds the .gltf only, and it loads from anywhere.
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  EXPECT_NE(readText(dir / "garment.gltf").find("data:application/octet-stream;base64,"), std::string::npos);
  expectGltfRoundTrip(dir / "garment.gltf", g);
}

TEST(MeshExportTest, GarmentPlyAndStlRoundTrip) {
  const Garment g = twoPanelGarment();
  const auto dir = freshDir("export_ply_stl");
  for (const char* name : {"garment.ply", "garment.stl"}) {
    SCOPED_TRACE(name);
    exportGarment(g, g.positions, dir / name);
    expectSameMesh(loadAvatar(dir / name), g.positions, g.triangles, 1e-6);
  }
  // PLY keeps UVs as well.
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile((dir / "garment.ply").string(), 0);
  ASSERT_NE(scene, nullptr) << importer.GetErrorString();
  ASSERT_EQ(scene->mNumMeshes, 1u);
  EXPECT_TRUE(scene->mMeshes[0]->HasTextureCoords(0));
}

TEST(MeshExportTest, PlainMeshRoundTripsInEveryFormat) {
  const TriangleMesh sphere = makeIcosphere(Eigen::Vector3d(0.1, 1.2, -0.3), 0.25, 2);
  const auto dir = freshDir("export_mesh");
  for (const char* name : {"sphere.obj", "sphere.glb", "sphere.gltf", "sphere.ply", "sphere.stl"}) {
    SCOPED_TRACE(name);
    exportMesh(sphere, dir / name);
    const TriangleMesh loaded = loadAvatar(dir / name);
    expectSameMesh(loaded, sphere.vertices, sphere.triangles, 1e-6);
    EXPECT_TRUE(isClosedManifold(loaded));
    EXPECT_NEAR(signedVolume(loaded), signedVolume(sphere), 1e-6);
  }
  EXPECT_FALSE(hasTemporaryFiles(dir));
}

TEST(MeshExportTest, ExportReplacesAnExistingFile) {
  const auto file = freshDir("export_replace") / "mesh.obj";
  exportMesh(makeBox(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()), file);
  exportMesh(makeIcosphere(Eigen::Vector3d::Zero(), 1.0, 1), file);
  EXPECT_EQ(loadAvatar(file).triangleCount(), 80);
}

TEST(MeshExportTest, UnknownExtensionListsValidOnes) {
  const Garment g = twoPanelGarment();
  const auto file = freshDir("export_bad") / "garment.fbx";
  try {
    exportGarment(g, g.positions, file);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              file.string() + ": unknown export format '.fbx' (valid: .obj, .glb, .gltf, .ply, .stl)");
  }
  EXPECT_FALSE(std::filesystem::exists(file));
}

TEST(MeshExportTest, BadStatesAreRefusedAndWriteNothing) {
  const Garment g = twoPanelGarment();
  const auto dir = freshDir("export_refused");
  Eigen::MatrixX3d nanPositions = g.positions;
  nanPositions(5, 2) = std::numeric_limits<double>::quiet_NaN();
  try {
    exportGarment(g, nanPositions, dir / "nan.obj");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "nan.obj").string() + ": cannot export: vertex 5 has a non-finite position");
  }
  EXPECT_THROW(exportGarment(g, g.positions.topRows(7), dir / "short.obj"), InputError);
  EXPECT_THROW(exportMesh(TriangleMesh{}, dir / "empty.glb"), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "nan.obj"));
  EXPECT_FALSE(std::filesystem::exists(dir / "short.obj"));
  EXPECT_FALSE(std::filesystem::exists(dir / "empty.glb"));
  EXPECT_FALSE(hasTemporaryFiles(dir));
}

TEST(MeshExportTest, MissingDirectoryNamesTheTarget) {
  const auto file = test::testOutputDir() / "no_such_directory" / "garment.glb";
  try {
    exportMesh(makeBox(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()), file);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + file.string() + ": directory does not exist");
  }
}

}  // namespace
}  // namespace drape
