// Issue #5, "cloth on a sphere": the Newton drape of the tablecloth settles on the sphere with no vertex deeper
// inside it than the contact thickness. Distances are measured against the analytic sphere, independently of
// the solver's own collider (an icosphere of the same radius). A cloth stretched over a ball, resting within its
// contact thickness, is a slow test (tests/slow/newton_contact_drum_test.cpp).
#include <gtest/gtest.h>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

TEST(NewtonContact, TableclothSettlesOnTheSphereWithoutPenetration) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "tablecloth.json";
  request.overrides = {{"mesh.target_edge_length", "0.05"}, {"solver.stage", "drape"}, {"solver.max_sim_time", "2.5"}};
  Simulation sim(loadScene(request));
  const Eigen::Vector3d centre(0.0, 0.5, 0.0);
  const double radius = 0.3;
  // The icosphere (subdivision 5) lies inside the analytic sphere by at most r (1 - cos(edge angle / 2)).
  const double facetSag = 0.3 * 1e-3;
  StepReport last;
  while (!sim.finished()) {
    last = sim.step();
    ASSERT_NE(last.status, StepStatus::Diverged) << "t = " << sim.time();
  }
  const Eigen::MatrixX3d x = sim.positions();
  ASSERT_TRUE(x.allFinite());
  double deepest = 0.0;
  int onTop = 0;
  for (int v = 0; v < x.rows(); ++v) {
    const double d = (x.row(v).transpose() - centre).norm() - radius;
    deepest = std::min(deepest, d);
    if (d < sim.contactThickness() + 0.01 && x(v, 1) > centre.y()) ++onTop;
  }
  EXPECT_GT(deepest, -(sim.contactThickness() + facetSag)) << "deepest vertex " << deepest << " m";
  EXPECT_GT(onTop, 20) << "the cloth lies on the sphere";
  EXPECT_GT(last.contacts, 20);
  // Settled: the kinetic-energy percentile is tiny (early stop, or close to it at the time limit).
  EXPECT_LT(last.kineticEnergy, 1e-6) << "t = " << sim.time() << (last.atRest ? " (at rest)" : "");
}

}  // namespace
}  // namespace drape::test
