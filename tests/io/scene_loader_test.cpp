// Scene files: good scenes load with their parts resolved; each malformed scene names the file and the element.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "drape/core/input_error.h"
#include "drape/garment/garment_builder.h"
#include "drape/scene/pins.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

MeshingOptions edgeLength(double target) {
  MeshingOptions o;
  o.targetEdgeLength = target;
  return o;
}

Scene load(const std::filesystem::path& file, std::vector<std::pair<std::string, std::string>> overrides = {}) {
  SceneRequest request;
  request.input = file;
  request.overrides = std::move(overrides);
  return loadScene(request);
}

TEST(SceneLoader, DefaultSceneHasPatternFabricAndSphere) {
  const Scene scene = load(assetsDir() / "scenes" / "tablecloth.json");
  EXPECT_EQ(scene.pattern.panels.size(), 1u);
  EXPECT_FALSE(scene.hasAvatar());
  ASSERT_EQ(scene.colliders.size(), 1u);
  const BoundingBox box = boundsOf(scene.colliders[0].mesh.vertices);
  EXPECT_NEAR(box.size().x(), 0.6, 0.01);
  EXPECT_NEAR(box.center().y(), 0.5, 1e-3);
  EXPECT_EQ(scene.fabric.name, "Cotton shirting");
  EXPECT_DOUBLE_EQ(scene.settings.number("mesh.target_edge_length"), 0.02);
}

TEST(SceneLoader, OverridesApplyOverTheFile) {
  const Scene scene = load(assetsDir() / "scenes" / "tablecloth.json",
                           {{"mesh.target_edge_length", "0.05"}, {"fabric.density", "0.3"}, {"fabric.preset", "denim"}});
  EXPECT_DOUBLE_EQ(scene.settings.number("mesh.target_edge_length"), 0.05);
  EXPECT_EQ(scene.fabric.name, "Denim");
  EXPECT_DOUBLE_EQ(scene.fabric.density, 0.3);  // the override wins over the preset's 0.41
  EXPECT_EQ(scene.settings.changed().count("fabric.density"), 1u);
}

TEST(SceneLoader, BarePatternBecomesAScene) {
  SceneRequest request;
  request.input = assetsDir() / "patterns" / "tablecloth.json";
  request.fabricPreset = "silk_charmeuse";
  const Scene scene = loadScene(request);
  EXPECT_EQ(scene.pattern.panels.size(), 1u);
  EXPECT_EQ(scene.fabric.name, "Silk charmeuse");
  EXPECT_TRUE(isPatternFile(request.input));
  EXPECT_FALSE(isPatternFile(assetsDir() / "scenes" / "tablecloth.json"));
}

TEST(SceneLoader, PinsResolveToTheTopCorners) {
  const Scene scene = load(assetsDir() / "scenes" / "hanging_cloth.json");
  const Garment garment = buildGarment(scene.pattern, meshingOptions(scene));
  const auto pinned = resolvePins(scene, garment);
  ASSERT_EQ(pinned.size(), 2u);
  for (int v : pinned) {
    EXPECT_NEAR(garment.positions(v, 1), 1.5, 1e-9);
    EXPECT_NEAR(std::abs(garment.positions(v, 0)), 0.5, 1e-9);
  }
}

TEST(SceneLoader, EdgePinSelectsTheWholeEdge) {
  SceneRequest request;
  request.input = testOutputDir() / "edge_pin_scene.json";
  {
    std::ofstream out(request.input);
    out << R"({"pattern": ")" << (assetsDir() / "patterns" / "hanging_cloth.json").string()
        << R"(", "pins": [{"panel": "cloth", "edge_label": "top"}], "mesh": {"target_edge_length": 0.1}})";
  }
  const Scene scene = loadScene(request);
  const Garment garment = buildGarment(scene.pattern, edgeLength(0.1));
  const auto pinned = resolvePins(scene, garment);
  EXPECT_EQ(pinned.size(), 11u);  // 1 m edge at 0.1 m: 10 segments, 11 vertices
  for (int v : pinned) EXPECT_NEAR(garment.positions(v, 1), 1.5, 1e-9);
}

TEST(SceneLoader, VertexPinsAndPinMotionLoad) {
  SceneRequest request;
  request.input = testOutputDir() / "moving_pin_scene.json";
  {
    std::ofstream out(request.input);
    out << R"({"pattern": ")" << (assetsDir() / "patterns" / "hanging_cloth.json").string()
        << R"(", "pins": [{"vertices": [3, 1, 3]},
                          {"panel": "cloth", "edge_label": "top",
                           "motion": {"start": 0.5, "end": 1.5, "translate": [0, 0.2, 0],
                                      "rotate": {"axis": [0, 0, 2], "center": [0, 1, 0], "degrees": 90}}}],
              "mesh": {"target_edge_length": 0.1}})";
  }
  const Scene scene = loadScene(request);
  ASSERT_EQ(scene.pins.size(), 2u);
  EXPECT_EQ(scene.pins[0].vertices, (std::vector<int>{3, 1, 3}));
  EXPECT_FALSE(scene.pins[0].moving);
  ASSERT_TRUE(scene.pins[1].moving);
  const PinMotion& m = scene.pins[1].motion;
  EXPECT_NEAR(m.angle, M_PI / 2, 1e-12);
  EXPECT_NEAR(m.axis.z(), 1.0, 1e-12);  // normalised
  const Garment garment = buildGarment(scene.pattern, edgeLength(0.1));
  const auto pinned = resolvePins(scene, garment);
  std::vector<int> expected = garment.edgeVertices.at(0).at(scene.pins[1].edge);
  expected.insert(expected.end(), {1, 3});
  std::sort(expected.begin(), expected.end());
  expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  EXPECT_EQ(pinned, expected);
  const auto motion = pinMotionIndex(scene, garment, pinned);
  for (size_t k = 0; k < pinned.size(); ++k) {
    const bool onTop = std::abs(garment.positions(pinned[k], 1) - 1.5) < 1e-9;
    EXPECT_EQ(motion[k], onTop ? 1 : -1) << "vertex " << pinned[k];
  }
}

TEST(PinMotion, RotatesAndTranslatesLinearlyInTime) {
  PinMotion m;
  m.start = 0.5;
  m.end = 1.5;
  m.center = Eigen::Vector3d(0, 1, 0);
  m.axis = Eigen::Vector3d::UnitX();
  m.angle = 0.75 * M_PI;
  m.translation = Eigen::Vector3d(0.1, 0, 0);
  const Eigen::Vector3d p0(0.5, 1.0, 0.3);
  EXPECT_TRUE(m.at(p0, 0.0).isApprox(p0));
  EXPECT_TRUE(m.at(p0, 0.5).isApprox(p0));
  // A right-handed turn by th about +x through (0, 1, 0), written out: y' = 1 + (y - 1) cos th - z sin th,
  // z' = (y - 1) sin th + z cos th; here y - 1 = 0 and z = 0.3.
  for (double t : {0.75, 1.0, 1.5, 2.5}) {
    const double s = std::clamp((t - 0.5) / 1.0, 0.0, 1.0);
    const double th = s * 0.75 * M_PI;
    const Eigen::Vector3d expected(0.5 + 0.1 * s, 1.0 - 0.3 * std::sin(th), 0.3 * std::cos(th));
    EXPECT_TRUE(m.at(p0, t).isApprox(expected, 1e-12)) << "t = " << t << ": " << m.at(p0, t).transpose();
  }
}

struct BadScene {
  const char* file;
  std::vector<const char*> expected;
};

class BadSceneTest : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, RaisesInputErrorNamingFileAndElement) {
  const BadScene& bad = GetParam();
  const auto file = testDataDir() / "bad" / bad.file;
  try {
    const Scene scene = load(file);
    // Pins that select nothing surface when they are resolved against the garment.
    const Garment garment = buildGarment(scene.pattern, meshingOptions(scene));
    resolvePins(scene, garment);
    FAIL() << bad.file << ": no error raised";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(bad.file), std::string::npos) << message;
    for (const char* part : bad.expected) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Files, BadSceneTest,
    ::testing::Values(
        BadScene{"scene_unknown_key.json", {"unknown key 'colour'", "valid keys"}},
        BadScene{"scene_missing_pattern.json", {"missing 'pattern'"}},
        BadScene{"scene_pattern_not_found.json", {"pattern: ", "no_such_pattern.json"}},
        BadScene{"scene_unknown_collider.json", {"collider 0", "unknown collider type 'cone'"}},
        BadScene{"scene_collider_bad_center.json", {"collider 0", "'center' must be [x, y, z]"}},
        BadScene{"scene_collider_negative_radius.json", {"collider 0", "radius must be positive"}},
        BadScene{"scene_pin_unknown_panel.json", {"pin 0", "no panel 'sleeve'"}},
        BadScene{"scene_pin_edge_out_of_range.json", {"pin 0", "has no edge 7"}},
        BadScene{"scene_pin_unknown_label.json", {"pin 0", "no edge labelled 'hem'"}},
        BadScene{"scene_pin_empty_region.json", {"pin 0", "selects no garment vertex"}},
        BadScene{"scene_pin_vertex_out_of_range.json", {"pin 0", "vertex 99999 is out of range", "vertices"}},
        BadScene{"scene_pin_negative_vertex.json", {"pin 0", "vertices[1] must be a vertex index"}},
        BadScene{"scene_pin_two_kinds.json", {"pin 0", "exactly one of 'panel'"}},
        BadScene{"scene_pin_motion_backwards.json", {"pin 0 motion", "'end' must be after 'start'"}},
        BadScene{"scene_pin_motion_zero_axis.json", {"pin 0 motion rotate", "'axis' must not be zero"}},
        BadScene{"scene_pin_motion_unknown_key.json", {"pin 0 motion", "unknown field 'spin'"}},
        BadScene{"scene_pin_motion_no_motion.json", {"pin 0 motion", "give 'rotate' and/or 'translate'"}},
        BadScene{"scene_panel_fabric_unknown_panel.json", {"panel_fabrics 'sleeve'", "no panel"}},
        BadScene{"scene_mesh_negative_edge.json", {"mesh.target_edge_length", "out of range"}},
        BadScene{"scene_mesh_edge_not_number.json", {"mesh.target_edge_length", "'fine' is not a number"}},
        BadScene{"scene_unknown_setting.json", {"unknown setting 'mesh.resolution'"}},
        BadScene{"scene_bad_avatar_units.json", {"avatar.units", "'inch' is not one of m cm mm in"}},
        BadScene{"scene_avatar_not_found.json", {"no_such_body.obj"}},
        BadScene{"scene_unknown_fabric.json", {"unknown fabric preset 'velvet'"}},
        BadScene{"scene_invalid_json.json", {"invalid JSON: parse error at line 2"}},
        BadScene{"scene_duplicate_setting.json", {"key 'mesh.target_edge_length' appears twice"}},
        BadScene{"scene_duplicate_collider_field.json", {"key 'colliders[0].radius' appears twice"}},
        BadScene{"scene_collider_huge_radius.json", {"collider 0", "radius 1e+308 m is too large (at most 100 m)"}},
        BadScene{"scene_collider_far_center.json",
                 {"collider 0", "field 'center': y = -1e+308 m is out of range [-100, 100] m"}},
        BadScene{"scene_collider_far_box.json", {"collider 0", "field 'max': y = 1e+300 m is out of range"}},
        BadScene{"scene_translate_too_far.json",
                 {"setting 'placement.translate'", "y = 1e+308 is out of range [-100, 100] m"}}),
    [](const auto& info) {
      std::string name = info.param.file;
      return name.substr(0, name.find('.'));
    });

TEST(SceneLoader, RealScenesOnMeanAllLoad) {
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  for (const char* name : {"shirt_mean_on_mean_all.json", "dress_pencil_on_mean_all.json",
                           "gpg_tee_on_mean_all.json", "gpg_skirt_2_panels_on_mean_all.json"}) {
    const Scene scene = load(testDataDir() / "scenes" / name);
    EXPECT_TRUE(scene.hasAvatar()) << name;
    // 23,752 in the file; assimp rebuilds vertices by position and merges the two coincident lip vertices.
    EXPECT_EQ(scene.avatar.vertexCount(), 23751) << name;
    EXPECT_GT(scene.pattern.panels.size(), 1u) << name;
  }
}

}  // namespace
}  // namespace drape::test

namespace drape::test {
namespace {

TEST(SceneLoader, CameraVectorsFromTheSceneFile) {
  SceneRequest request;
  request.input = testOutputDir() / "camera_scene.json";
  {
    std::ofstream out(request.input);
    out << R"({"pattern": ")" << (assetsDir() / "patterns" / "tablecloth.json").string()
        << R"(", "camera": {"eye": [0, 2.5, 3], "target": [0, 0.8, 0], "fov_deg": 30}})";
  }
  const Scene scene = loadScene(request);
  EXPECT_TRUE(scene.settings.vector3("camera.eye").isApprox(Eigen::Vector3d(0, 2.5, 3)));
  EXPECT_TRUE(scene.settings.vector3("camera.target").isApprox(Eigen::Vector3d(0, 0.8, 0)));
  EXPECT_DOUBLE_EQ(scene.settings.number("camera.fov_deg"), 30);
}

}  // namespace
}  // namespace drape::test

namespace drape::test {
namespace {

TEST(SceneLoader, DefaultSceneIsTheTshirtOnTheDefaultMannequin) {
  const Scene scene = load(assetsDir() / "scenes" / "default.json");
  EXPECT_TRUE(scene.hasAvatar());
  EXPECT_GT(scene.pattern.panels.size(), 3u);
  EXPECT_GT(scene.pattern.stitches.size(), 3u);
  const BoundingBox body = boundsOf(scene.avatar.vertices);
  EXPECT_NEAR(body.min.y(), 0.0, 0.01);  // feet on the floor
  EXPECT_GT(body.size().y(), 1.5);
  const Garment garment = buildGarment(scene.pattern, meshingOptions(scene));
  EXPECT_FALSE(garment.stitchPairs.empty());
}

}  // namespace
}  // namespace drape::test

namespace drape::test {
namespace {

TEST(SceneLoader, QualityThresholdsFromTheSceneFile) {
  SceneRequest request;
  request.input = testOutputDir() / "quality_scene.json";
  {
    std::ofstream out(request.input);
    out << R"({"pattern": ")" << (assetsDir() / "patterns" / "tablecloth.json").string()
        << R"(", "quality": {"require_rest": false, "max_strain": 0.3, "max_self_intersections": 7}})";
  }
  const Scene scene = loadScene(request);
  EXPECT_FALSE(scene.settings.flag("quality.require_rest"));
  EXPECT_DOUBLE_EQ(scene.settings.number("quality.max_strain"), 0.3);
  EXPECT_EQ(scene.settings.integer("quality.max_self_intersections"), 7);
}

}  // namespace
}  // namespace drape::test
