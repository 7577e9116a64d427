// placement.translate (scene_garment.h): the scene file's "placement" section moves every placed vertex by exactly
// the vector, the rest shape and the mesh stay as they are, region pins select in the moved frame, and a garment
// whose centre lies outside the avatar's bounding box draws one warning naming the pattern file and the setting.
#include <gtest/gtest.h>

#include <fstream>

#include "drape/core/input_error.h"
#include "drape/scene/pins.h"
#include "drape/scene/scene.h"
#include "drape/sim/scene_garment.h"
#include "shared_data.h"

namespace drape::test {
namespace {

Scene load(const std::filesystem::path& file, std::vector<std::pair<std::string, std::string>> overrides = {}) {
  SceneRequest request;
  request.input = file;
  request.overrides = std::move(overrides);
  return loadScene(request);
}

int placementWarnings(const Diagnostics& diagnostics, const Scene& scene) {
  int n = 0;
  for (const std::string& w : diagnostics.warnings())
    n += w.find("placement.translate") != std::string::npos && w.find(scene.patternFile.string()) != std::string::npos;
  return n;
}

TEST(ScenePlacement, TranslateMovesEveryPlacedVertexByExactlyTheVector) {
  const std::filesystem::path file = testOutputDir() / "placement_scene.json";
  {
    std::ofstream out(file);
    out << R"({"pattern": ")" << (assetsDir() / "patterns" / "tshirt.json").string()
        << R"(", "mesh": {"target_edge_length": 0.05}, "placement": {"translate": [0.1, -0.25, 0.4]}})";
  }
  const Scene moved = load(file);
  EXPECT_TRUE(moved.settings.vector3("placement.translate").isApprox(Eigen::Vector3d(0.1, -0.25, 0.4)));
  const Scene asPlaced = load(file, {{"placement.translate", "0,0,0"}});
  Diagnostics d1, d2;
  const Garment a = buildSceneGarment(asPlaced, &d1);
  const Garment b = buildSceneGarment(moved, &d2);
  ASSERT_EQ(a.vertexCount(), b.vertexCount());
  ASSERT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.rest, b.rest);
  for (int v = 0; v < a.vertexCount(); ++v)
    ASSERT_NEAR((b.positions.row(v) - a.positions.row(v) - Eigen::RowVector3d(0.1, -0.25, 0.4)).norm(), 0.0, 1e-12)
        << "vertex " << v;
}

TEST(ScenePlacement, RegionPinsSelectInTheMovedFrame) {
  const std::filesystem::path scene = assetsDir() / "scenes" / "hanging_cloth.json";
  const Scene original = load(scene, {{"mesh.target_edge_length", "0.05"}});
  const Scene moved = load(scene, {{"mesh.target_edge_length", "0.05"}, {"placement.translate", "0,0,0.1"}});
  Diagnostics d;
  const auto pinnedOriginal = resolvePins(original, buildSceneGarment(original, &d));
  ASSERT_FALSE(pinnedOriginal.empty());
  // The scene's region pins stay where the file says; the cloth moved 10 cm along z, out of them, and a pin that
  // selects nothing is an error.
  bool regionPins = false;
  for (const PinSpec& pin : moved.pins) regionPins |= pin.byRegion;
  ASSERT_TRUE(regionPins);
  EXPECT_THROW(resolvePins(moved, buildSceneGarment(moved, &d)), InputError);
}

TEST(ScenePlacement, GarmentAwayFromTheAvatarIsWarnedAbout) {
  const std::filesystem::path scene = assetsDir() / "scenes" / "default.json";
  const Scene onTheBody = load(scene, {{"mesh.target_edge_length", "0.05"}});
  ASSERT_TRUE(onTheBody.hasAvatar());
  Diagnostics none;
  buildSceneGarment(onTheBody, &none);
  EXPECT_EQ(placementWarnings(none, onTheBody), 0);

  for (const char* offset : {"0,-1.5,0", "0,2,0", "1.5,0,0", "0,0,-1"}) {
    // With placement.fit off: the fit would move the garment back onto the body (placement_fit_test.cpp).
    const Scene away =
        load(scene, {{"mesh.target_edge_length", "0.05"}, {"placement.translate", offset}, {"placement.fit", "false"}});
    Diagnostics warned;
    buildSceneGarment(away, &warned);
    EXPECT_EQ(placementWarnings(warned, away), 1) << offset;
  }
}

}  // namespace
}  // namespace drape::test
