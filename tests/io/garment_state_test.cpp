// Garment states read back from the OBJ that exportGarment writes (drape --from): round trip, and every way a file
// can fail to be this garment's state, each refused with the file (and line) named.
#include "drape/io/garment_state.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "drape/core/input_error.h"
#include "drape/io/mesh_export.h"

namespace drape {
namespace {

const std::filesystem::path kDir = std::filesystem::path(DRAPE_TEST_OUTPUT_DIR) / "garment_state";

// A 3 x 3 grid of vertices, 8 triangles, two panels (the left and right columns of squares).
Garment gridGarment() {
  Garment g;
  g.panelNames = {"left", "right"};
  g.rest.resize(9, 2);
  g.positions.resize(9, 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      g.rest.row(3 * j + i) << 0.1 * i, 0.1 * j;
      g.positions.row(3 * j + i) << 0.1 * i, 1.0 + 0.1 * j, 0.05 * i * j;
    }
  g.uvs = g.rest;
  g.triangles.resize(8, 3);
  g.trianglePanel.resize(8);
  int f = 0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 3 * j + i;
      g.triangles.row(f) << a, a + 1, a + 4;
      g.trianglePanel(f++) = i;
      g.triangles.row(f) << a, a + 4, a + 3;
      g.trianglePanel(f++) = i;
    }
  g.vertexPanel = Eigen::VectorXi::Zero(9);
  return g;
}

std::filesystem::path writeText(const std::string& name, const std::string& text) {
  std::filesystem::create_directories(kDir);
  const std::filesystem::path file = kDir / name;
  std::ofstream(file) << text;
  return file;
}

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The message of the InputError that f throws ("" when it throws none).
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// An exported draped state, its text with line `from` replaced by `to`.
std::filesystem::path editedExport(const std::string& name, const std::string& from, const std::string& to) {
  const Garment g = gridGarment();
  const std::filesystem::path file = kDir / name;
  std::filesystem::create_directories(kDir);
  exportGarment(g, g.positions, file);
  std::string text = readText(file);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return writeText(name, text);
}

TEST(GarmentState, ExportedDrapeReadsBackAsTheSameState) {
  const Garment g = gridGarment();
  Eigen::MatrixX3d draped = g.positions;
  draped.col(1).array() -= 0.25;
  draped(4, 2) = 1.0 / 3.0;  // a coordinate that 9 significant digits round
  std::filesystem::create_directories(kDir);
  const std::filesystem::path file = kDir / "draped.obj";
  exportGarment(g, draped, file);
  const GarmentState state = readGarmentState(file);
  ASSERT_EQ(state.positions.rows(), 9);
  EXPECT_LT((state.positions - draped).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(state.faces.rows(), 8);
  EXPECT_NO_THROW(checkGarmentState(state, g, file));
}

TEST(GarmentState, PositionsWithoutFacesAreCheckedByCountOnly) {
  const Garment g = gridGarment();
  std::string text = "# positions only\n";
  for (int v = 0; v < 9; ++v) text += "v " + std::to_string(v) + " 1 2 0.5 0.5 0.5\n";  // colours ignored
  const std::filesystem::path file = writeText("positions.obj", text);
  const GarmentState state = readGarmentState(file);
  EXPECT_EQ(state.positions(7, 0), 7.0);
  EXPECT_EQ(state.faces.rows(), 0);
  EXPECT_NO_THROW(checkGarmentState(state, g, file));
  const std::filesystem::path shorter = writeText("eight.obj", text.substr(0, text.rfind("v ")));
  const std::string error = errorOf([&] { checkGarmentState(readGarmentState(shorter), g, shorter); });
  EXPECT_NE(error.find("eight.obj: 8 vertices, the scene's garment has 9"), std::string::npos) << error;
}

TEST(GarmentState, BadLinesAreRefusedWithFileAndLine) {
  const std::filesystem::path nan = writeText("nan.obj", "v 0 0 0\nv 1 nan 0\n");
  EXPECT_NE(errorOf([&] { readGarmentState(nan); }).find("nan.obj:2: vertex needs three finite coordinates"),
            std::string::npos);
  const std::filesystem::path two = writeText("two.obj", "v 0 0 0\nv 1 0\n");
  EXPECT_NE(errorOf([&] { readGarmentState(two); }).find("two.obj:2:"), std::string::npos);
  const std::filesystem::path quad = writeText("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  EXPECT_NE(errorOf([&] { readGarmentState(quad); }).find("quad.obj:5: face is not a triangle"), std::string::npos);
  const std::filesystem::path far = writeText("far.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1/1/1 2//2 4\n");
  EXPECT_NE(errorOf([&] { readGarmentState(far); }).find("far.obj:4: face corner '4' names no vertex"),
            std::string::npos);
  const std::filesystem::path empty = writeText("empty.obj", "# nothing\n");
  EXPECT_NE(errorOf([&] { readGarmentState(empty); }).find("empty.obj: no vertices"), std::string::npos);
  EXPECT_NE(errorOf([&] { readGarmentState(kDir / "missing.obj"); }).find("missing.obj: cannot open"),
            std::string::npos);
  const std::filesystem::path glb = writeText("state.glb", "glTF");
  EXPECT_NE(errorOf([&] { readGarmentState(glb); }).find("state.glb: a garment state must be an OBJ"),
            std::string::npos);
}

TEST(GarmentState, NegativeFaceIndicesCountBackFromTheLastVertex) {
  const std::filesystem::path file = writeText("relative.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\n");
  const GarmentState state = readGarmentState(file);
  ASSERT_EQ(state.faces.rows(), 1);
  EXPECT_EQ(state.faces.row(0), Eigen::RowVector3i(0, 1, 2));
}

TEST(GarmentState, AnotherGarmentsFacesAreRefused) {
  const Garment g = gridGarment();
  // The first face of the export (grid triangle 0 1 4, written 1-based) turned over: the same vertices, another
  // orientation, as a tool that reorders vertices might leave it.
  const std::filesystem::path flipped = editedExport("flipped.obj", "f 1/1/1 2/2/2 5/5/5", "f 2/2/2 1/1/1 5/5/5");
  std::string error = errorOf([&] { checkGarmentState(readGarmentState(flipped), g, flipped); });
  EXPECT_NE(error.find("face 2 1 5 is not a triangle of the scene's garment"), std::string::npos) << error;
  EXPECT_NE(error.find("flipped.obj:"), std::string::npos) << error;
  const std::filesystem::path twice = editedExport("twice.obj", "f 1/1/1 5/5/5 4/4/4", "f 1/1/1 2/2/2 5/5/5");
  error = errorOf([&] { checkGarmentState(readGarmentState(twice), g, twice); });
  EXPECT_NE(error.find("appears twice"), std::string::npos) << error;
  const std::filesystem::path fewer = editedExport("fewer.obj", "f 1/1/1 5/5/5 4/4/4\n", "");
  error = errorOf([&] { checkGarmentState(readGarmentState(fewer), g, fewer); });
  EXPECT_NE(error.find("fewer.obj: 7 faces, the scene's garment has 8 triangles"), std::string::npos) << error;
}

}  // namespace
}  // namespace drape
