// A free fall, however far, is not an explosion: the tablecloth with nothing to hold it together (the softest stretch
// stiffness the settings admit, no shear or bending stiffness, 1000 m/s^2 gravity and 0.1 s steps) runs to its time
// limit. That an exploded garment ends the run Diverged in every stage, with the state before the step that exploded
// kept, is a slow test (tests/slow/exploded_state_stages_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "exploded_state_support.h"
#include "shared_data.h"

namespace drape::test {
namespace {

TEST(ExplodedState, AFreeFallIsNotAnExplosion) {
  // The soft tablecloth slides off the sphere and falls tens of metres at 1000 m/s^2 in 0.5 s, far outside the
  // scene's 2 m box but within the distance gravity carries it: the run ends at its time limit.
  auto overrides = nothingHoldsIt();
  overrides.emplace_back("solver.stage", "drape");
  Simulation sim(sceneWith("tablecloth.json", overrides));
  double lowest = 0.0;
  while (!sim.finished()) {
    const StepReport r = sim.step();
    ASSERT_NE(r.status, StepStatus::Diverged) << sim.divergedReason();
  }
  for (int v = 0; v < sim.positions().rows(); ++v) lowest = std::min(lowest, sim.positions()(v, 1));
  EXPECT_LT(lowest, -20.0);
  EXPECT_EQ(sim.endReason(), "MaxSimTime");
  EXPECT_TRUE(sim.divergedReason().empty());
}

}  // namespace
}  // namespace drape::test
