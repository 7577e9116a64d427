#include <gtest/gtest.h>

#include "drape/core/input_error.h"
#include "drape/scene/settings.h"

namespace drape {
namespace {

TEST(Settings, DefaultsAndTypedAccess) {
  Settings s;
  EXPECT_DOUBLE_EQ(s.number("mesh.target_edge_length"), 0.01);
  EXPECT_EQ(s.text("avatar.units"), "m");
  EXPECT_FALSE(s.has("fabric.density"));
  EXPECT_TRUE(s.changed().empty());
}

TEST(Settings, SetValidatesTypeRangeAndChoice) {
  Settings s;
  s.set("mesh.target_edge_length", "0.005", "test");
  EXPECT_DOUBLE_EQ(s.number("mesh.target_edge_length"), 0.005);
  EXPECT_THROW(s.set("mesh.target_edge_length", "0", "test"), InputError);      // below the minimum
  EXPECT_THROW(s.set("mesh.target_edge_length", "1e-3x", "test"), InputError);  // trailing garbage
  EXPECT_THROW(s.set("mesh.target_edge_length", "nan", "test"), InputError);
  EXPECT_THROW(s.set("avatar.units", "feet", "test"), InputError);
  s.set("avatar.units", "cm", "test");
  EXPECT_EQ(s.text("avatar.units"), "cm");
  EXPECT_EQ(s.changed().size(), 2u);
}

TEST(Settings, UnknownKeyListsEveryValidKey) {
  Settings s;
  try {
    s.set("mesh.size", "1", "--set");
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("unknown setting 'mesh.size'"), std::string::npos);
    for (const auto& spec : Settings::specs()) EXPECT_NE(m.find(spec.key), std::string::npos) << spec.key;
  }
}

// A scene written for a setting that was replaced is refused with a line that names the replacement.
TEST(Settings, ReplacedKeysNameTheirReplacement) {
  Settings s;
  const std::vector<std::pair<std::string, std::string>> replaced = {
      {"solver.newton.early_stop_threshold", "solver.newton.rest_speed"}, {"solver.damping.stretch", "fabric.damping"}};
  for (const auto& [old, replacement] : replaced) {
    EXPECT_FALSE(Settings::find(old)) << old;
    ASSERT_TRUE(Settings::find(replacement)) << replacement;
    try {
      s.set(old, "0", "scene.json");
      ADD_FAILURE() << old << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("scene.json: the setting '" + old + "' is replaced by " + replacement, 0), 0u)
          << e.what();
    }
  }
}

TEST(Settings, EverySpecDefaultIsValid) {
  for (const auto& spec : Settings::specs()) {
    Settings s;
    if (!spec.defaultValue.empty()) EXPECT_NO_THROW(s.set(spec.key, spec.defaultValue, "default")) << spec.key;
  }
}

}  // namespace
}  // namespace drape

namespace drape {
namespace {

TEST(Settings, Vector3ParsesThreeNumbers) {
  Settings s;
  EXPECT_FALSE(s.has("camera.eye"));
  s.set("camera.eye", "0.5, 1.5,-3", "test");
  EXPECT_TRUE(s.vector3("camera.eye").isApprox(Eigen::Vector3d(0.5, 1.5, -3)));
  EXPECT_TRUE(s.vector3("camera.up").isApprox(Eigen::Vector3d::UnitY()));
  for (const char* bad : {"1,2", "1,2,3,4", "a,b,c", "1,,3", "1,2,nan"})
    EXPECT_THROW(s.set("camera.eye", bad, "test"), InputError) << bad;
}

}  // namespace
}  // namespace drape
