// Issue #5, "cloth on a sphere": the Newton drape of the tablecloth settles on the sphere with no vertex deeper
// inside it than the contact thickness. Distances are measured against the analytic sphere, independently of
// the solver's own collider (an icosphere of the same radius).
#include <gtest/gtest.h>

#include <fstream>

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

// A cloth stretched over a ball like a drum skin (its four edges pinned 4 cm below the ball's top) presses on it
// with the membrane's tension: the vertices on the ball rest within the contact band, at least half the contact
// thickness off the ball's surface, instead of being pressed onto it (at the paper's penalty of 1e2 N/m the
// tightest of them rest 0.5 mm off it).
TEST(NewtonContact, StretchedClothRestsWithinItsContactThickness) {
  const std::filesystem::path scene = testOutputDir() / "drum_over_ball.json";
  std::ofstream(scene) << R"({"pattern": ")" << (assetsDir() / "patterns" / "tablecloth.json").generic_string() << R"(",
    "fabric": {"preset": "cotton_shirting"},
    "colliders": [{"type": "sphere", "center": [0.0, 0.94, 0.0], "radius": 0.1, "subdivisions": 5}],
    "pins": [{"panel": "cloth", "edge": 0}, {"panel": "cloth", "edge": 1}, {"panel": "cloth", "edge": 2},
             {"panel": "cloth", "edge": 3}],
    "mesh": {"target_edge_length": 0.02}, "solver": {"stage": "drape", "max_sim_time": 1.5}})";
  SceneRequest request;
  request.input = scene;
  Simulation sim(loadScene(request));
  while (!sim.finished()) ASSERT_NE(sim.step().status, StepStatus::Diverged) << "t = " << sim.time();
  EXPECT_EQ(sim.endReason(), "AtRest");
  const double thickness = sim.contactThickness();
  const double facetSag = 0.1 * 1e-3;  // the icosphere lies inside the analytic sphere by at most this much
  const Eigen::MatrixX3d x = sim.positions();
  int onBall = 0;
  double nearest = 1.0;
  for (int v = 0; v < x.rows(); ++v) {
    const double d = (x.row(v).transpose() - Eigen::Vector3d(0.0, 0.94, 0.0)).norm() - 0.1;
    if (d > thickness + facetSag) continue;
    ++onBall;
    nearest = std::min(nearest, d);
  }
  EXPECT_GT(onBall, 10) << "the cloth does not rest on the ball";
  EXPECT_GT(nearest, 0.5 * thickness - facetSag) << "a vertex on the ball rests " << 1e3 * nearest << " mm off it";
}

}  // namespace
}  // namespace drape::test
