// The preview -> drape hand-off of the full pipeline: when the preview hands over (hand-off speed held for 0.1 s,
// or its time limit), that the drape stage goes on from the preview stage's positions, velocities and time alone,
// and how it starts (no second initial relaxation unless asked for). The hand-offs of whole library drapes are slow
// tests (tests/slow/pipeline_handoff_drape_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "drape/newton/newton_solver.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "pipeline_handoff_support.h"

namespace drape::test {
namespace {

Scene coarseTablecloth(const Overrides& extra) {
  Overrides overrides = {{"mesh.target_edge_length", "0.08"}, {"solver.stage", "full"}};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  return libraryScene("tablecloth.json", std::move(overrides));
}

// Steps until the drape has run one step; returns that step's report and the scene time the drape started at.
StepReport firstDrapeStep(Simulation& sim, double* handoffTime) {
  for (int i = 0; i < 10000 && sim.stage() == Stage::Preview; ++i) sim.step();
  *handoffTime = sim.time();
  return sim.step();
}

TEST(PipelineHandoff, DrapeFromThePreviewSkipsTheInitialRelaxation) {
  const std::pair<std::string, std::string> shortPreview{"solver.preview.max_time", "0.05"};
  // At the paper's 1 ms step limit the coarse tablecloth's drape grows without a split, so that the growth rule
  // alone sets the step count.
  const std::pair<std::string, std::string> paperStep{"solver.newton.h_max", "1e-3"};
  Simulation plain(coarseTablecloth({shortPreview, paperStep}));
  double t0 = 0.0;
  const StepReport first = firstDrapeStep(plain, &t0);
  EXPECT_EQ(first.stage, Stage::Drape);
  // It starts at h_max and grows by the time-splitting rule to h_max times
  // solver.newton.h_max_factor_after_preview, never beyond.
  const double hMax = plain.scene().settings.number("solver.newton.h_max");
  const double settleStep = hMax * plain.scene().settings.number("solver.newton.h_max_factor_after_preview");
  EXPECT_DOUBLE_EQ(first.h, hMax);
  int steps = 1;
  double h = first.h;
  while (h < settleStep && steps < 200) {
    const StepReport r = plain.step();
    ASSERT_EQ(r.stage, Stage::Drape);
    ASSERT_NE(r.status, StepStatus::Diverged);
    EXPECT_LE(r.h, settleStep);
    h = r.h;
    ++steps;
  }
  EXPECT_DOUBLE_EQ(h, settleStep);
  // log(factor) / log(1 / omega) growths of I_s steps each, and the first one's own step.
  const double omega = plain.scene().settings.number("solver.newton.omega");
  const int growAfter = plain.scene().settings.integer("solver.newton.grow_after_steps");
  const int growths = static_cast<int>(std::ceil(std::log(settleStep / hMax) / std::log(1.0 / omega) - 1e-9));
  std::printf("[ PipelineHandoff ] the drape reached %.1f ms after %d steps\n", 1e3 * settleStep, steps);
  EXPECT_EQ(steps, growAfter * growths + 1);
  for (int k = 0; k < 10; ++k) EXPECT_DOUBLE_EQ(plain.step().h, settleStep);

  Simulation relaxed(coarseTablecloth({shortPreview, paperStep, {"solver.newton.relaxation_after_preview", "true"}}));
  const StepReport firstRelaxed = firstDrapeStep(relaxed, &t0);
  EXPECT_DOUBLE_EQ(firstRelaxed.h, settleStep / 16.0);

  Simulation unscaled(coarseTablecloth({shortPreview, paperStep, {"solver.newton.h_max_factor_after_preview", "1"}}));
  EXPECT_DOUBLE_EQ(firstDrapeStep(unscaled, &t0).h, unscaled.scene().settings.number("solver.newton.h_max"));

  // A drape from the placed garment keeps its relaxation.
  Simulation direct(libraryScene("tablecloth.json", {{"mesh.target_edge_length", "0.08"}, {"solver.stage", "drape"}}));
  EXPECT_DOUBLE_EQ(direct.step().h, direct.scene().settings.number("solver.newton.h_max") / 16.0);
}

TEST(PipelineHandoff, PreviewHandsOverOnceTheHandoffSpeedHeldForTheWindow) {
  // Every speed is below 100 m/s: the hand-off comes after the 0.1 s window, which opens once the preview's initial
  // relaxation (the drape's: its first 0.1 s, velocities zeroed) is over, long before the 0.5 s limit. A relaxing
  // cloth moves at most g h per step whatever its forces, so no window opens before the relaxation ends.
  Simulation eager(coarseTablecloth({{"solver.preview.handoff_speed", "100"}}));
  const double relaxation = newton::NewtonSettings{}.relaxationTime;
  const double h = eager.settings().preview.timeStep;
  double handoff = 0.0;
  firstDrapeStep(eager, &handoff);
  EXPECT_GE(handoff, relaxation + 0.1 - 1e-9);
  EXPECT_LT(handoff, relaxation + 0.1 + 3 * h);
  // No speed is below 0: the preview runs to its time limit.
  Simulation never(coarseTablecloth({{"solver.preview.handoff_speed", "0"}, {"solver.preview.max_time", "0.3"}}));
  firstDrapeStep(never, &handoff);
  EXPECT_GE(handoff, 0.3 - 1e-9);
  EXPECT_LT(handoff, 0.3 + h + 1e-9);
}

// DESIGN.md 5b: Simulation holds one stage; the drape stage that follows the preview is built from the preview's
// positions, velocities and time alone. Mid-fall (the preview's time limit well after its relaxation), the velocities
// carried over are the preview's last step's: Backward Euler's x_{n+1} = x_n + h v_{n+1}, computed here from the two
// states around the hand-over.
TEST(PipelineHandoff, DrapeStageContinuesFromThePreviewStagesPositionsVelocitiesAndTime) {
  Simulation sim(coarseTablecloth({{"solver.preview.handoff_speed", "0"}, {"solver.preview.max_time", "0.15"}}));
  ResumeState before;
  StepReport last;
  while (sim.stage() == Stage::Preview && !sim.finished()) {
    before = sim.resumeState();
    last = sim.step();
    ASSERT_NE(last.status, StepStatus::Diverged);
  }
  ASSERT_EQ(sim.stage(), Stage::Drape);
  EXPECT_EQ(last.stage, Stage::Preview);
  const ResumeState after = sim.resumeState();
  EXPECT_EQ(after.stage, Stage::Drape);
  EXPECT_DOUBLE_EQ(after.time, last.time);
  EXPECT_DOUBLE_EQ(after.previewTime, last.time);
  EXPECT_EQ((after.previewPositions - after.positions).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::MatrixX3d stepVelocity = (after.positions - before.positions) / last.h;
  const double fastest = stepVelocity.rowwise().norm().maxCoeff();
  ASSERT_GT(fastest, 0.05) << "the tablecloth is not falling at the hand-over";
  EXPECT_LT((after.velocities - stepVelocity).rowwise().norm().maxCoeff(), 1e-9 * fastest + 1e-12);
  // Nothing of the preview's step control carries over: the drape starts at its own h_max, without relaxation.
  const StepReport first = sim.step();
  EXPECT_EQ(first.stage, Stage::Drape);
  EXPECT_FALSE(first.relaxing);
  EXPECT_DOUBLE_EQ(first.h, sim.settings().drape.newton.hMax);
  EXPECT_NEAR(first.time, after.time + first.h, 1e-12);
}

// A preview run alone stops at rest by the drape's own test on the same model, and says so; a drape started from
// that state finds it at rest too and barely moves it. The default t-shirt on a coarse mesh.
TEST(PipelineHandoff, PreviewAloneStopsAtRestByTheDrapesTest) {
  Simulation preview(libraryScene("default.json", {{"mesh.target_edge_length", "0.035"}, {"solver.stage", "preview"}}));
  StepReport last;
  while (!preview.finished()) {
    last = preview.step();
    ASSERT_NE(last.status, StepStatus::Diverged);
  }
  ASSERT_EQ(preview.endReason(), "AtRest") << "at t = " << preview.time() << " s";
  EXPECT_TRUE(last.atRest);
  EXPECT_EQ(preview.snapshot().stage, Stage::Done);
  ResumeState rest = preview.resumeState();
  rest.stage = Stage::Drape;
  rest.previewPositions = rest.positions;
  rest.previewTime = rest.time;
  Simulation drape(libraryScene("default.json", {{"mesh.target_edge_length", "0.035"}, {"solver.stage", "drape"}}),
                   rest);
  ASSERT_TRUE(drape.resumed());
  while (!drape.finished()) ASSERT_NE(drape.step().status, StepStatus::Diverged);
  EXPECT_EQ(drape.endReason(), "AtRest");
  const double moved = (drape.positions() - rest.positions).rowwise().norm().mean();
  std::printf("[ PipelineHandoff ] the drape moved the preview's rest state %.3f mm mean\n", 1e3 * moved);
  EXPECT_LT(moved, 1e-3);
}

// A preview run alone that has settled (Newton's steps) and is pulled again goes back to L-BFGS's long steps, follows
// the drag, and comes to rest again once let go.
TEST(PipelineHandoff, SettledPreviewDraggedAgainTakesItsLongStepsAndRestsAgain) {
  Simulation sim(libraryScene("default.json", {{"mesh.target_edge_length", "0.035"},
                                               {"solver.stage", "preview"},
                                               {"solver.max_sim_time", "4"}}));  // time to settle twice
  StepReport last;
  while (!sim.finished()) last = sim.step();
  ASSERT_EQ(sim.endReason(), "AtRest");
  EXPECT_FALSE(last.quasiNewton);  // settled by Newton's steps
  // The lowest vertex of the hem, pulled 5 cm outward, horizontally away from the garment's axis (not into the body).
  const Eigen::MatrixX3d rest = sim.positions();
  Eigen::Index grabbed = 0;
  rest.col(1).minCoeff(&grabbed);
  Eigen::Vector3d outward = rest.row(grabbed).transpose() - rest.colwise().mean().transpose();
  outward.y() = 0.0;
  const Eigen::Vector3d target = rest.row(grabbed).transpose() + 0.05 * outward.normalized();
  sim.setDrag(static_cast<int>(grabbed), target);
  EXPECT_FALSE(sim.finished());
  for (int i = 0; i < 30; ++i) {
    last = sim.step();
    ASSERT_NE(last.status, StepStatus::Diverged);
    EXPECT_TRUE(last.quasiNewton) << "step " << i;
    EXPECT_EQ(last.stage, Stage::Preview);
  }
  const double before = (rest.row(grabbed).transpose() - target).norm();
  const double after = (sim.positions().row(grabbed).transpose() - target).norm();
  std::printf("[ PipelineHandoff ] dragged vertex %.1f -> %.1f mm from the target\n", 1e3 * before, 1e3 * after);
  EXPECT_LT(after, 0.5 * before);
  sim.setDrag(-1, Eigen::Vector3d::Zero());
  while (!sim.finished()) ASSERT_NE(sim.step().status, StepStatus::Diverged);
  EXPECT_EQ(sim.endReason(), "AtRest");
}

}  // namespace
}  // namespace drape::test
