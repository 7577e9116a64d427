#pragma once
// What the untangling tests share (tests/unit/sim/untangle_test.cpp, tests/slow/untangle_drag_test.cpp): a quality
// check's value, and a curtain dragged through another and let go.
//
// Two curtains hang 3 cm apart (tests/data/scenes/two_curtains_framed.json, self-contact on), the back one held along
// all four edges. The front one's centre is dragged `depth` behind where it hung and held there for 0.3 s, deep enough
// to tent through the back one; let go, the front curtain is back on its side of the back one, uncrossed, 0.2 s later.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "drape/sim/drape_quality.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {

inline double qualityValue(const Simulation& sim, const char* name) {
  const QualityCheck* c = checkDrapeQuality(sim, "AtRest").find(name);
  return c ? c->value : -1.0;
}

inline void draggedThroughComesBack(const char* stage, double depth) {
  SceneRequest request;
  request.input = testDataDir() / "scenes" / "two_curtains_framed.json";
  request.overrides = {{"solver.stage", stage}, {"solver.max_sim_time", "1"}};
  Simulation sim(loadScene(request));
  const Eigen::MatrixX3d placed = sim.positions();
  int centre = 0;
  (placed.rowwise() - Eigen::RowVector3d(0.0, 1.3, 0.0)).rowwise().squaredNorm().minCoeff(&centre);
  ASSERT_NEAR(placed(centre, 2), 0.0, 1e-9) << "a vertex of the front curtain";
  sim.setDrag(centre, Eigen::Vector3d(0.0, 1.3, -depth));
  while (sim.time() < 0.3 - 1e-9) ASSERT_NE(sim.step().status, StepStatus::Diverged) << stage;
  const double held = qualityValue(sim, "self_intersections");
  const double heldAt = sim.positions()(centre, 2);
  sim.setDrag(-1, Eigen::Vector3d::Zero());
  while (!sim.finished() && sim.time() < 0.5 - 1e-9) ASSERT_NE(sim.step().status, StepStatus::Diverged) << stage;
  const double after = qualityValue(sim, "self_intersections");
  // The back curtain's z next to the dragged vertex (nearest in x and y): the front one must be in front of it.
  const Eigen::MatrixX3d x = sim.positions();
  double backZ = 0.0, nearest = INFINITY;
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    if (placed(v, 2) > -0.02) continue;  // the front curtain
    const double d = std::hypot(x(v, 0) - x(centre, 0), x(v, 1) - x(centre, 1));
    if (d < nearest) nearest = d, backZ = x(v, 2);
  }
  std::printf("%s, dragged %.0f cm: its centre held at z = %.1f mm, %.0f crossing pairs; let go, %.0f 0.2 s later, "
              "its centre %.1f mm in front of the back curtain\n",
              stage, 1e2 * depth, 1e3 * heldAt, held, after, 1e3 * (x(centre, 2) - backZ));
  EXPECT_LT(heldAt, -0.035) << stage << ": the drag took it past the back curtain";
  EXPECT_GT(held, 10.0) << stage;
  EXPECT_EQ(after, 0.0) << stage;
  EXPECT_GT(x(centre, 2), backZ) << stage;
}

}  // namespace drape::test
