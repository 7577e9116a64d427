// The quasi-Newton preview (the default preview) on the default scene: Newton's rest state is its rest
// state, and it settles every fabric preset at its long step without tearing or entering the body. Its step and
// preconditioner are checked in tests/unit/sim/quasi_newton_preview_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "drape/collision/avatar_collider.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "quasi_newton_preview_support.h"

namespace drape::test {
namespace {

TEST(QuasiNewtonPreview, NewtonsRestStateIsItsRestState) {
  Simulation alone(defaultScene("drape"));
  while (!alone.finished()) ASSERT_NE(alone.step().status, StepStatus::Diverged);
  ASSERT_EQ(alone.endReason(), "AtRest");
  const Eigen::MatrixX3d rest = alone.positions();

  Simulation preview(defaultScene("preview", {{"solver.max_sim_time", "0.5"}}), startStateAt(StagePlan::Preview, rest));
  ASSERT_TRUE(preview.resumed());
  while (!preview.finished()) ASSERT_NE(preview.step().status, StepStatus::Diverged);
  const double mean = (preview.positions() - rest).rowwise().norm().mean();
  std::printf("[ QuasiNewtonPreview ] from Newton's rest state: %s after %.3f s, %.3f mm from it on average\n",
              preview.endReason().c_str(), preview.time(), 1e3 * mean);
  EXPECT_LT(mean, 1e-3);  // issue 47's target for a faithful preview
}

TEST(QuasiNewtonPreview, EveryFabricPresetSettlesAtTheLongStep) {
  for (const char* fabric :
       {"jersey_knit", "cotton_shirting", "denim", "polyester_chiffon", "silk_charmeuse", "wool_suiting"}) {
    Simulation sim(defaultScene("preview", {{"fabric.preset", fabric}, {"solver.max_sim_time", "0.5"}}));
    double largestStrain = 0.0;
    int steps = 0;
    while (!sim.finished()) {
      const StepReport r = sim.step();
      ASSERT_NE(r.status, StepStatus::Diverged) << fabric;
      if (r.time > 0.2 && r.quasiNewton) {  // L-BFGS grown to the long step after the relaxation
        EXPECT_NEAR(r.h, 1.0 / 120.0, 1e-12) << fabric;
      }
      largestStrain = std::max(largestStrain, r.maxStrain);
      ++steps;
    }
    const Eigen::MatrixX3d x = sim.positions();
    ASSERT_TRUE(x.allFinite()) << fabric;
    int inside = 0;
    for (Eigen::Index v = 0; v < x.rows(); ++v)
      inside += sim.collider()->signedDistance(x.row(v).transpose()) < -sim.contactThickness();
    const StepReport last = sim.step();
    std::printf("[ QuasiNewtonPreview ] %s: %d steps, largest strain %.2f, final %.3f, %d vertices inside the body\n",
                fabric, steps, largestStrain, last.maxStrain, inside);
    EXPECT_LT(last.maxStrain, 1.0) << fabric;  // whole (the quality verdict's stretch limit)
    EXPECT_EQ(inside, 0) << fabric;
  }
}

}  // namespace
}  // namespace drape::test
