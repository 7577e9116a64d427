// The default preview on every library garment in every fabric preset (issue "One model"): it settles, at rest by
// the drape's own test, without tearing, NaN or a vertex inside the body. One test per garment, its presets in turn.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>

#include "drape/collision/avatar_collider.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

// Garment and preset pairs the preview does not yet settle whole (docs/BENCHMARKS.md, "One model"): run and reported,
// held to no divergence and no NaN only. The trousers in cotton shirting tear at the feet (216 %, 5 vertices 10 mm
// inside); the shirt over the skirt in jersey is still moving at 3 s.
const std::set<std::string> kOpen = {"trousers in cotton_shirting", "shirt_over_skirt in jersey_knit"};

class PreviewLibraryPresets : public ::testing::TestWithParam<const char*> {};

TEST_P(PreviewLibraryPresets, SettlesWholeAndOutsideTheBody) {
  for (const char* fabric :
       {"jersey_knit", "cotton_shirting", "denim", "polyester_chiffon", "silk_charmeuse", "wool_suiting"}) {
    SCOPED_TRACE(fabric);
    SceneRequest request;
    request.input = assetsDir() / "scenes" / (std::string(GetParam()) + ".json");
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
        "[ PreviewLibraryPresets ] %s in %s: %s at %.2f s after %d steps, largest strain %.1f %%, deepest "
        "%.1f mm\n",
        GetParam(), fabric, sim.endReason().c_str(), sim.time(), sim.steps(), 100.0 * last.maxStrain, -1e3 * deepest);
    if (kOpen.count(std::string(GetParam()) + " in " + fabric)) continue;
    EXPECT_EQ(sim.endReason(), "AtRest");
    EXPECT_LT(last.maxStrain, 1.0);  // whole: the quality verdict's stretch limit
    EXPECT_EQ(inside, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Library, PreviewLibraryPresets,
                         ::testing::Values("default", "tshirt", "aline_skirt", "trousers", "sleeveless_dress",
                                           "shirt_over_skirt"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

}  // namespace
}  // namespace drape::test
