// The drape's early stop waits for the garment's vertices to slow down: when it says AtRest, the 99th percentile of
// the vertices' speeds over the last step, from the positions before and after it, is below solver.newton.rest_speed.
// A threshold on the vertices' kinetic energy took a light fabric, whose vertices weigh little, for at rest while it
// still fell onto the body.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

double speedPercentile(const Eigen::MatrixX3d& before, const Eigen::MatrixX3d& after, double h, double p) {
  std::vector<double> speeds(static_cast<size_t>(after.rows()));
  for (Eigen::Index i = 0; i < after.rows(); ++i) speeds[static_cast<size_t>(i)] = (after.row(i) - before.row(i)).norm() / h;
  std::sort(speeds.begin(), speeds.end());
  return speeds[static_cast<size_t>(p * static_cast<double>(speeds.size() - 1))];
}

TEST(EarlyStop, ALightGarmentIsAtRestOnlyOnceItsVerticesAreSlow) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "default.json";
  request.overrides = {{"mesh.target_edge_length", "0.03"},
                       {"fabric.density", "1e-4"},  // the lightest fabric the settings allow
                       {"solver.stage", "drape"},
                       {"solver.max_sim_time", "2"}};
  Simulation sim(loadScene(request));
  Eigen::MatrixX3d before = sim.positions();
  StepReport last;
  while (!sim.finished()) {
    before = sim.positions();
    last = sim.step();
    ASSERT_NE(last.status, StepStatus::Diverged) << "t = " << sim.time();
  }
  ASSERT_EQ(sim.endReason(), "AtRest") << "t = " << sim.time();
  const double speed = speedPercentile(before, sim.positions(), last.h, 0.99);
  EXPECT_LT(speed, 0.02) << "at rest at t = " << sim.time() << " s with the 99th percentile of speeds at " << speed
                         << " m/s";
}

}  // namespace
}  // namespace drape::test
