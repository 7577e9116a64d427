// An exploded garment ends the run Diverged in every stage (drape, both previews, the pipeline), with the state before
// the step that exploded kept and the triangle that tore named. The exploding scene is the default t-shirt with
// nothing to hold it together but the body's friction (exploded_state_support.h); a free fall is checked in
// tests/unit/sim/exploded_state_test.cpp.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "drape/geometry/strain.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "exploded_state_support.h"
#include "shared_data.h"

namespace drape::test {
namespace {

struct Stage {
  const char* name;
  std::vector<std::pair<std::string, std::string>> settings;
};

TEST(ExplodedState, EndsDivergedInEveryStageWithTheStateBeforeIt) {
  const std::vector<Stage> stages = {
      {"drape", {{"solver.stage", "drape"}}},
      {"preview", {{"solver.stage", "preview"}}},
      {"pipeline", {{"solver.stage", "full"}}}};
  for (const Stage& stage : stages) {
    SCOPED_TRACE(stage.name);
    auto overrides = nothingHoldsItButTheBody();
    overrides.insert(overrides.end(), stage.settings.begin(), stage.settings.end());
    Simulation sim(sceneWith("default.json", overrides));
    Eigen::MatrixX3d before = sim.positions();
    StepReport last;
    while (!sim.finished()) {
      before = sim.positions();
      last = sim.step();
      if (last.status == StepStatus::Diverged) break;
    }
    ASSERT_EQ(last.status, StepStatus::Diverged) << "ended " << sim.endReason() << " at t = " << sim.time();
    const std::string& why = sim.divergedReason();
    EXPECT_NE(why.find("exploded"), std::string::npos) << why;
    EXPECT_NE(why.find(" of panel '"), std::string::npos) << why;
    // The state kept is the one before the step, and the garment in it is not exploded.
    EXPECT_TRUE(sim.positions().isApprox(before, 0.0)) << why;
    const Eigen::VectorXd stretch = triangleStretch(sim.garment().rest, sim.positions(), sim.garment().triangles);
    EXPECT_LE(stretch.maxCoeff(), 100.0);
    EXPECT_GT(last.maxStrain, 100.0);
    // Nothing steps on from there.
    const int steps = sim.steps();
    EXPECT_EQ(sim.step().status, StepStatus::Diverged);
    EXPECT_EQ(sim.steps(), steps);
    EXPECT_TRUE(sim.positions().isApprox(before, 0.0));
  }
}

}  // namespace
}  // namespace drape::test
