// The preview -> drape hand-off of the full pipeline on library garments: the drape's longer steps after the preview
// settle the default scene to nearly the same drape as h_max itself. The rest of the hand-off's tests are in
// tests/unit/sim/pipeline_handoff_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "pipeline_handoff_support.h"

namespace drape::test {
namespace {

// The longer steps of the drape after the preview settle it to nearly the same drape as h_max itself: the default
// scene at 3.5 cm, run to the scene's time limit (1.5 s) with solver.newton.h_max_factor_after_preview 1, 3 and 10
// (3 ms: 1.2 mm apart on average when written; 1 ms and 3 ms on the 1.5 cm default scene: 0.8 mm; 3 and 10 ms on the
// library garments 0.1-1.7 mm, docs/BENCHMARKS.md).
TEST(PipelineHandoff, LongerStepsAfterThePreviewSettleToNearlyTheSameDrape) {
  auto drape = [](const char* factor, int* drapeSteps) {
    Simulation sim(libraryScene("default.json", {{"solver.stage", "full"},
                                                 {"mesh.target_edge_length", "0.035"},
                                                 {"solver.newton.h_max_factor_after_preview", factor}}));
    *drapeSteps = 0;
    while (!sim.finished()) {
      const StepReport r = sim.step();
      EXPECT_NE(r.status, StepStatus::Diverged);
      *drapeSteps += r.stage == Stage::Drape;
    }
    return Eigen::MatrixX3d(sim.positions());
  };
  int steps1 = 0, steps3 = 0, steps10 = 0;
  const Eigen::MatrixX3d x1 = drape("1", &steps1);
  const Eigen::MatrixX3d x3 = drape("3", &steps3);
  const Eigen::MatrixX3d x10 = drape("10", &steps10);  // the default
  const double mean3 = (x3 - x1).rowwise().norm().mean(), mean10 = (x10 - x1).rowwise().norm().mean();
  std::printf(
      "[ PipelineHandoff ] drape steps %d (h_max), %d (3 h_max) and %d (10 h_max); drapes %.2f and %.2f mm "
      "from h_max's on average\n",
      steps1, steps3, steps10, 1e3 * mean3, 1e3 * mean10);
  EXPECT_LT(steps3, steps1 / 2);
  EXPECT_LT(steps10, steps3 * 2 / 3);
  EXPECT_LT(mean3, 3e-3);
  EXPECT_LT(mean10, 3e-3);
}

}  // namespace
}  // namespace drape::test
