// The extremes grid's cells (drape/sim/extremes_grid.h): every physics setting at both ends of its range, each a value
// the settings accept. The grid run on the library t-shirt is a slow test (tests/slow/extremes_grid_tshirt_test.cpp).
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "drape/scene/settings.h"
#include "drape/sim/extremes_grid.h"
#include "shared_data.h"

namespace drape::test {
namespace {

TEST(ExtremesGrid, CellsCoverEveryPhysicsSettingAtBothEndsOfItsRange) {
  const auto cells = extremeCells();
  std::set<std::string> keys;
  for (const auto& cell : cells)
    for (const auto& [key, value] : cell.settings) {
      ASSERT_NE(Settings::find(key), nullptr) << key;
      Settings settings;
      EXPECT_NO_THROW(settings.set(key, value, "grid")) << cell.name << ": " << key << "=" << value;
      keys.insert(key);
    }
  for (const char* key : {"fabric.stretch_warp", "fabric.stretch_weft", "fabric.shear", "fabric.bend_warp",
                          "fabric.bend_weft", "fabric.density", "fabric.friction", "fabric.thickness", "sim.gravity",
                          "fabric.damping", "mesh.target_edge_length", "solver.newton.h_max", "solver.preview.time_step",
                          "solver.newton.tolerance", "solver.cg.tolerance"})
    EXPECT_EQ(keys.count(key), 1u) << key;
  // Each axis at its range's minimum and maximum: the stretch cells are the spec's own ends.
  const SettingSpec* stretch = Settings::find("fabric.stretch_warp");
  bool atMin = false, atMax = false;
  for (const auto& cell : cells)
    for (const auto& [key, value] : cell.settings)
      if (key == "fabric.stretch_warp") {
        atMin |= std::stod(value) == stretch->min;
        atMax |= std::stod(value) == stretch->max;
      }
  EXPECT_TRUE(atMin && atMax);
}

// The cells where a much stiffer term (a rigid bending plate, the stiffest fabric on a 1 m mesh at 0.1 s steps) could
// win over contact and leave vertices inside the body: the preview holds the body there, on the default scene for the
// grid's 0.2 s.
TEST(ExtremesGrid, PreviewHoldsTheBodyUnderTheStiffestTerms) {
  SceneRequest base;
  base.input = assetsDir() / "scenes" / "default.json";
  for (const ExtremeCell& cell : extremeCells()) {
    if (cell.name != "bending max" && cell.name != "stiffest + coarsest + largest step") continue;
    const ExtremeOutcome o = runExtremeCell(base, cell, "preview", 0.2, 2000);
    EXPECT_TRUE(o.failure.empty()) << cell.name << ": " << o.failure;
    EXPECT_GT(o.steps, 0) << cell.name;
  }
}

}  // namespace
}  // namespace drape::test
