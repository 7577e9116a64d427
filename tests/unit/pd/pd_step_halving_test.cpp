// PreviewSolver's step halving (preview_settings.h maxHalvings): a step whose L-G loop hits the cap is redone from
// the step's start at half the time step, and converged steps let the time step grow back. The L-G tolerance is
// a move, so it tightens with the step relative to the motion: at rest a hanging cloth's first iteration moves
// about h^2 g, 4x less at h / 2 (the residuals quoted below are measured on this cloth).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "drape/pd/grid_cloth.h"
#include "drape/pd/preview_solver.h"

namespace drape::pd {
namespace {

drape::model::ClothModel hangingCloth() {
  GridClothOptions o;
  o.nx = o.ny = 16;
  return makeGridCloth(o);
}

// One L-G iteration per attempt: the residual after it decides.
PreviewSettings oneIteration(double tolerance, int maxHalvings) {
  PreviewSettings s;
  s.domains = 2;
  s.threads = 2;
  s.maxIterations = 1;
  s.tolerance = tolerance;
  s.maxHalvings = maxHalvings;
  s.growAfterSteps = 3;
  return s;
}

TEST(PdStepHalving, CappedStepIsRedoneFromItsStartAtHalfTheStep) {
  const drape::model::ClothModel model = hangingCloth();
  // The first iteration at h = 1/120 s moves ~5e-4 of the cloth's size, at h / 4 ~16x less: 1e-5 is beyond both.
  const PreviewSettings s = oneIteration(1e-5, 2);
  PreviewSolver solver(model, s);
  const PreviewReport r = solver.step();
  EXPECT_EQ(r.status, PreviewStatus::MaxIterations);  // the smallest step keeps its capped attempt
  EXPECT_EQ(r.splits, 2);
  EXPECT_EQ(r.iterations, 3);  // one per attempt: the report counts the redone work
  EXPECT_DOUBLE_EQ(r.timeStep, s.timeStep / 4);
  EXPECT_DOUBLE_EQ(solver.time(), s.timeStep / 4);

  // Independent run: a solver whose own step is h / 4 takes the same step from the same state.
  PreviewSettings quarter = s;
  quarter.timeStep = s.timeStep / 4;
  quarter.maxHalvings = 0;
  PreviewSolver reference(model, quarter);
  const PreviewReport q = reference.step();
  EXPECT_EQ(q.splits, 0);
  EXPECT_LT((solver.positions() - reference.positions()).norm(), 1e-12 * reference.positions().norm());
  EXPECT_LT((solver.velocities() - reference.velocities()).norm(), 1e-9 * (1.0 + reference.velocities().norm()));

  // Capped at the smallest step: no further halving, no growth.
  const PreviewReport next = solver.step();
  EXPECT_EQ(next.splits, 0);
  EXPECT_DOUBLE_EQ(next.timeStep, s.timeStep / 4);

  // maxHalvings = 0 keeps the paper's step even when capped.
  PreviewSolver fixed(model, oneIteration(1e-5, 0));
  const PreviewReport f = fixed.step();
  EXPECT_EQ(f.splits, 0);
  EXPECT_DOUBLE_EQ(f.timeStep, s.timeStep);
}

TEST(PdStepHalving, ConvergedStepsGrowTheStepBack) {
  // The falling cloth's first iteration moves up to ~9e-4 of its size around step 4 and ~7e-4 once it hangs at
  // rest: with a tolerance of 8e-4 the swing needs h / 2, and the hanging cloth converges at h again.
  const PreviewSettings s = oneIteration(8e-4, 1);
  PreviewSolver solver(hangingCloth(), s);
  std::vector<PreviewReport> reports;
  double time = 0.0;
  for (int i = 0; i < 80; ++i) {
    reports.push_back(solver.step());
    ASSERT_NE(reports.back().status, PreviewStatus::Diverged);
    time += reports.back().timeStep;
  }
  EXPECT_NEAR(solver.time(), time, 1e-12);
  int halved = 0, splits = 0, firstHalved = -1;
  for (size_t i = 0; i < reports.size(); ++i) {
    const PreviewReport& r = reports[i];
    splits += r.splits;
    if (r.timeStep < s.timeStep) {
      ++halved;
      if (firstHalved < 0) firstHalved = static_cast<int>(i);
      EXPECT_DOUBLE_EQ(r.timeStep, s.timeStep / 2);
    }
    // A step at h either converged or was redone; one at h / 2 converged or is kept capped.
    if (r.timeStep == s.timeStep) {
      EXPECT_EQ(r.status, PreviewStatus::Converged) << "step " << i;
    }
  }
  std::printf("[ PdStepHalving ] %d of %zu steps at h/2 (first: step %d), %d attempts redone\n", halved,
              reports.size(), firstHalved, splits);
  EXPECT_GT(halved, 0);
  EXPECT_GT(splits, 0);
  // Back at h once hanging: the last steps converge at the full step.
  for (size_t i = reports.size() - 10; i < reports.size(); ++i) {
    EXPECT_DOUBLE_EQ(reports[i].timeStep, s.timeStep) << "step " << i;
    EXPECT_EQ(reports[i].splits, 0) << "step " << i;
  }
}

}  // namespace
}  // namespace drape::pd
