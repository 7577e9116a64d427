// The default preview on every library garment in every fabric preset (issue "One model"): it settles, at rest by
// the drape's own test, without tearing, NaN or a vertex inside the body. One test per garment and preset, so that
// the suite's parallel runs share them out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <tuple>

#include "drape/collision/avatar_collider.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

class PreviewLibraryPresets : public ::testing::TestWithParam<std::tuple<const char*, const char*>> {};

TEST_P(PreviewLibraryPresets, SettlesWholeAndOutsideTheBody) {
  const auto [garment, fabric] = GetParam();
  SceneRequest request;
  request.input = assetsDir() / "scenes" / (std::string(garment) + ".json");
  request.overrides = {{"solver.stage", "preview"}, {"fabric.preset", fabric}};
  Simulation sim(loadScene(request));
  StepReport last;
  while (!sim.finished()) {
    last = sim.step();
    ASSERT_NE(last.status, StepStatus::Diverged) << "t = " << last.time << ": " << sim.divergedReason();
  }
  const Eigen::MatrixX3d x = sim.positions();
  ASSERT_TRUE(x.allFinite());
  int inside = 0;
  double deepest = 0.0;
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const double d = sim.collider()->signedDistance(x.row(v).transpose());
    deepest = std::min(deepest, d);
    inside += d < -sim.contactThickness();
  }
  std::printf(
      "[ PreviewLibraryPresets ] %s in %s: %s at %.2f s after %d steps, largest strain %.1f %%, deepest %.1f mm\n",
      garment, fabric, sim.endReason().c_str(), sim.time(), sim.steps(), 100.0 * last.maxStrain, -1e3 * deepest);
  EXPECT_EQ(sim.endReason(), "AtRest");
  EXPECT_LT(last.maxStrain, 1.0);  // whole: the quality verdict's stretch limit
  EXPECT_EQ(inside, 0);
}

INSTANTIATE_TEST_SUITE_P(
    Library, PreviewLibraryPresets,
    ::testing::Combine(::testing::Values("default", "tshirt", "aline_skirt", "trousers", "sleeveless_dress",
                                         "shirt_over_skirt"),
                       ::testing::Values("jersey_knit", "cotton_shirting", "denim", "polyester_chiffon",
                                         "silk_charmeuse", "wool_suiting")),
    [](const ::testing::TestParamInfo<std::tuple<const char*, const char*>>& info) {
      return std::string(std::get<0>(info.param)) + "_in_" + std::get<1>(info.param);
    });

}  // namespace
}  // namespace drape::test
