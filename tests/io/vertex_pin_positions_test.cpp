// Vertex pins with saved placed positions ("at"): parsed, checked (count, shape, only on vertex pins), and resolved
// by position so that a renumbered mesh pins the same cloth points; a position that no vertex is near any more is an
// error naming the file, the pin and the entry.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>

#include "drape/core/input_error.h"
#include "drape/garment/garment_builder.h"
#include "drape/scene/pins.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

constexpr double kEdge = 0.1;  // mesh.target_edge_length of the scenes below

std::string point(const Eigen::Vector3d& p) {
  std::ostringstream out;
  out.precision(17);
  out << "[" << p.x() << ", " << p.y() << ", " << p.z() << "]";
  return out.str();
}

// A hanging-cloth scene whose "pins" list is pinsJson; returns its path.
std::filesystem::path writeScene(const std::string& name, const std::string& pinsJson) {
  const std::filesystem::path file = testOutputDir() / name;
  std::ofstream out(file);
  out << R"({"pattern": ")" << (assetsDir() / "patterns" / "hanging_cloth.json").string() << R"(", "pins": )"
      << pinsJson << R"(, "mesh": {"target_edge_length": )" << kEdge << "}}";
  return file;
}

Scene load(const std::filesystem::path& file) {
  SceneRequest request;
  request.input = file;
  return loadScene(request);
}

Garment garmentOf(const Scene& scene) {
  MeshingOptions o;
  o.targetEdgeLength = scene.settings.number("mesh.target_edge_length");
  return buildGarment(scene.pattern, o);
}

// The message of the InputError that f throws ("" when none).
template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The placed garment of the scenes below (pins do not change the mesh). ctest runs each test in its own process, two
// at a time: each writes its reference scene under its own test's name, so that one process never reads the file
// while another truncates it.
const Garment& referenceGarment() {
  static const Garment g = garmentOf(load(writeScene(
      std::string("pin_at_reference_") + ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".json",
      "[]")));
  return g;
}

Eigen::Vector3d placed(int v) {
  return referenceGarment().positions.row(v).transpose();
}

TEST(VertexPinPositions, AtIsParsedWithItsVertices) {
  const Garment& g = referenceGarment();
  ASSERT_GT(g.vertexCount(), 40);
  const auto file = writeScene("pin_at_parsed.json", "[{\"vertices\": [5, 17], \"at\": [" + point(placed(5)) + ", " +
                                                         point(placed(17)) + "]}, {\"vertices\": [3]}]");
  const Scene scene = load(file);
  ASSERT_EQ(scene.pins.size(), 2u);
  EXPECT_EQ(scene.pins[0].vertices, (std::vector<int>{5, 17}));
  ASSERT_EQ(scene.pins[0].at.size(), 2u);
  EXPECT_EQ(scene.pins[0].at[0], placed(5));  // 17 significant digits: exact
  EXPECT_EQ(scene.pins[0].at[1], placed(17));
  EXPECT_TRUE(scene.pins[1].at.empty()) << "an old vertex pin has no positions";
  EXPECT_EQ(resolvePins(scene, garmentOf(scene)), (std::vector<int>{3, 5, 17}));
}

TEST(VertexPinPositions, WrongIndexWithTheRightPositionPinsTheRightVertex) {
  // The indices are swapped and one is out of range: the positions decide.
  const auto file =
      writeScene("pin_at_wrong_index.json", "[{\"vertices\": [17, 100000, 5], \"at\": [" + point(placed(5)) + ", " +
                                                point(placed(30)) + ", " + point(placed(17)) + "]}]");
  const Scene scene = load(file);
  const Garment g = garmentOf(scene);
  EXPECT_EQ(pinVertices(scene.pins[0], scene, g), (std::vector<int>{5, 30, 17}));
  EXPECT_EQ(resolvePins(scene, g), (std::vector<int>{5, 17, 30}));
  // The whole simulation pins them too.
  const Simulation simulation(scene);
  EXPECT_EQ(simulation.pinned(), (std::vector<int>{5, 17, 30}));
}

TEST(VertexPinPositions, RenumberedMeshPinsTheSameClothPoints) {
  // Saved on one numbering, loaded on a shuffled one (what a new ordering of the mesher does): the pins follow the
  // positions to the new indices.
  const Garment& g = referenceGarment();
  const std::vector<int> saved = {0, 7, 21, g.vertexCount() - 1};
  std::string at;
  for (int v : saved) at += (at.empty() ? "" : ", ") + point(placed(v));
  const Scene scene =
      load(writeScene("pin_at_renumbered.json", "[{\"vertices\": [0, 7, 21, " + std::to_string(g.vertexCount() - 1) +
                                                    "], \"at\": [" + at + "]}]"));
  std::vector<int> newIndex(g.vertexCount());
  std::iota(newIndex.begin(), newIndex.end(), 0);
  std::shuffle(newIndex.begin(), newIndex.end(), std::mt19937(7));
  Garment renumbered = g;
  for (int v = 0; v < g.vertexCount(); ++v) renumbered.positions.row(newIndex[v]) = g.positions.row(v);
  std::vector<int> expected;
  for (int v : saved) expected.push_back(newIndex[v]);
  EXPECT_EQ(pinVertices(scene.pins[0], scene, renumbered), expected);
  // Without "at" the same file pins other vertices: the silent failure this format guards against.
  PinSpec bare = scene.pins[0];
  bare.at.clear();
  EXPECT_NE(pinVertices(bare, scene, renumbered), expected);
}

TEST(VertexPinPositions, SmallDriftResolvesToTheNearestVertexAndCoincidentVerticesKeepTheIndex) {
  const Scene scene =
      load(writeScene("pin_at_drift.json", "[{\"vertices\": [5], \"at\": [" +
                                               point(placed(12) + Eigen::Vector3d(0.001, -0.002, 0.0)) + "]}]"));
  Garment g = garmentOf(scene);
  // Tolerance: a quarter of the 0.1 m target edge, capped at 5 mm.
  EXPECT_DOUBLE_EQ(vertexPinTolerance(scene), 0.005);
  EXPECT_EQ(pinVertices(scene.pins[0], scene, g), std::vector<int>{12});
  // Two vertices at the same place (as two panels' seam vertices may be): the index given is kept.
  g.positions.row(20) = g.positions.row(12);
  PinSpec pin = scene.pins[0];
  pin.at = {placed(12)};
  for (int given : {12, 20}) {
    pin.vertices = {given};
    EXPECT_EQ(pinVertices(pin, scene, g), std::vector<int>{given});
  }
}

TEST(VertexPinPositions, FarPositionIsAnErrorNamingFilePinAndEntry) {
  // 41 mm in front of vertex 17 (the cloth hangs in the z = 0 plane, so no vertex is nearer).
  const Eigen::Vector3d far = placed(17) + Eigen::Vector3d(0.0, 0.0, 0.041);
  const auto file = writeScene("pin_at_far.json",
                               "[{\"panel\": \"cloth\", \"edge_label\": \"top\"}, "
                               "{\"vertices\": [5, 17], \"at\": [" +
                                   point(placed(5)) + ", " + point(far) + "]}]");
  const Scene scene = load(file);
  const std::string message = errorOf([&] { resolvePins(scene, garmentOf(scene)); });
  EXPECT_NE(message.find("pin_at_far.json: pin 1: vertices[1] was saved at ("), std::string::npos) << message;
  char expectedAt[64];
  std::snprintf(expectedAt, sizeof expectedAt, "(%.3f, %.3f, %.3f)", far.x(), far.y(), far.z());
  EXPECT_NE(message.find(expectedAt), std::string::npos) << message;
  EXPECT_NE(message.find("nearest garment vertex is 41.0 mm away"), std::string::npos) << message;
  EXPECT_NE(message.find("re-pin it"), std::string::npos) << message;
  // The Simulation (what the CLI and the GUI build) reports the same.
  EXPECT_EQ(errorOf([&] { Simulation simulation(scene); }), message);
}

TEST(VertexPinPositions, MalformedAtNamesTheElement) {
  const std::string p5 = point(placed(5));
  struct Case {
    std::string pins;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"[{\"vertices\": [5, 17], \"at\": [" + p5 + "]}]", "pin 0: 'at' has 1 positions but 'vertices' has 2 entries"},
      {"[{\"vertices\": [5], \"at\": " + p5 + "}]", "pin 0: 'at' has 3 positions but 'vertices' has 1 entries"},
      {"[{\"vertices\": [5], \"at\": 3}]", "pin 0: 'at' must be a list of [x, y, z] positions"},
      {"[{\"vertices\": [5, 6], \"at\": [" + p5 + ", [0, 1]]}]", "pin 0: at[1] must be [x, y, z] (metres)"},
      {"[{\"vertices\": [5], \"at\": [[0, \"1\", 2]]}]", "pin 0: at[0] must hold three finite numbers"},
      {"[{\"vertices\": [5]}, {\"panel\": \"cloth\", \"edge\": 0, \"at\": [" + p5 + "]}]",
       "pin 1: 'at' belongs to a vertex pin"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto file = writeScene("pin_at_bad_" + std::to_string(i) + ".json", cases[i].pins);
    const std::string message = errorOf([&] { load(file); });
    EXPECT_NE(message.find("pin_at_bad_" + std::to_string(i) + ".json: " + cases[i].expected), std::string::npos)
        << "case " << i << ": " << message;
  }
}

TEST(VertexPinPositions, PinsWithoutAtKeepTheIndexBehaviour) {
  const Scene scene = load(writeScene("pin_no_at.json", "[{\"vertices\": [17, 5]}]"));
  const Garment g = garmentOf(scene);
  EXPECT_EQ(pinVertices(scene.pins[0], scene, g), (std::vector<int>{17, 5}));
  const Scene bad = load(writeScene("pin_no_at_range.json", "[{\"vertices\": [100000]}]"));
  EXPECT_NE(errorOf([&] { resolvePins(bad, g); }).find("pin 0: vertex 100000 is out of range"), std::string::npos);
}

}  // namespace
}  // namespace drape::test
