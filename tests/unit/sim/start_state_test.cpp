// Stages started at given positions (drape::startStateAt, drape --from): the drape started at its own rest state
// stays there, and the preview and the pipeline start where they are told to.
#include <gtest/gtest.h>

#include <cstdio>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

Scene defaultScene(const char* stage) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "default.json";
  request.overrides = {{"solver.stage", stage}, {"mesh.target_edge_length", "0.035"}};
  return loadScene(request);
}

Eigen::MatrixX3d runToEnd(Simulation& sim, int* steps) {
  *steps = 0;
  while (!sim.finished()) {
    const StepReport r = sim.step();
    EXPECT_NE(r.status, StepStatus::Diverged);
    ++*steps;
  }
  return sim.positions();
}

TEST(StartState, NewtonsRestStateIsAFixedPointOfTheDrapeStartedAtIt) {
  Simulation alone(defaultScene("drape"));
  int steps = 0;
  const Eigen::MatrixX3d rest = runToEnd(alone, &steps);
  ASSERT_EQ(alone.endReason(), "AtRest");

  Simulation again(defaultScene("drape"), startStateAt(StagePlan::Drape, rest));
  ASSERT_TRUE(again.resumed());
  EXPECT_DOUBLE_EQ(again.time(), 0.0);
  int againSteps = 0;
  const Eigen::MatrixX3d x = runToEnd(again, &againSteps);
  const double mean = (x - rest).rowwise().norm().mean();
  std::printf(
      "[ StartState ] Newton alone at rest after %d steps (%.3f s); from that state at rest again after %d "
      "steps (%.3f s), %.3f mm from it on average\n",
      steps, alone.time(), againSteps, again.time(), 1e3 * mean);
  EXPECT_EQ(again.endReason(), "AtRest");
  // Little more than the early-stop window: the drape from the placed garment took three times as long and more.
  EXPECT_LT(again.time(), alone.time() / 2.0);
  EXPECT_LT(mean, 0.5e-3);
}

TEST(StartState, PreviewAndPipelineStartAtTheGivenPositions) {
  Simulation placed(defaultScene("preview"));
  for (int i = 0; i < 40; ++i) placed.step();
  const Eigen::MatrixX3d moved = placed.positions();  // not the placed garment: the seams have pulled it
  Simulation fresh(defaultScene("preview"));
  ASSERT_GT((moved - fresh.positions()).rowwise().norm().mean(), 0.01);

  for (const char* stage : {"preview", "full"}) {
    const Scene scene = defaultScene(stage);
    Simulation sim(scene, startStateAt(scene.settings.stagePlan(), moved));
    ASSERT_TRUE(sim.resumed()) << stage;
    EXPECT_EQ(sim.stage(), Stage::Preview) << stage;
    EXPECT_EQ((sim.positions() - moved).cwiseAbs().maxCoeff(), 0.0) << stage;
    const StepReport r = sim.step();
    EXPECT_EQ(r.stage, Stage::Preview) << stage;
    // At rest at the start (velocities zero): one step moves a vertex by what the forces do in 1/480 s, far less
    // than the 1 cm back to the placed garment.
    EXPECT_LT((sim.positions() - moved).rowwise().norm().mean(), 2e-3) << stage;
  }
}

// The GUI's Drape after a preview that ran to solver.max_sim_time (SimulationWorker::startDrape): the drape built from
// that preview state has the time limit of its own, so it runs instead of finishing at once.
TEST(StartState, DrapeFromAPreviewThatRanToTheLimitHasItsOwnTimeLimit) {
  Scene preview = defaultScene("preview");
  preview.settings.set("solver.max_sim_time", "0.04", "test");
  Simulation sim(preview);
  while (!sim.finished()) sim.step();
  ASSERT_EQ(sim.endReason(), "MaxSimTime");
  ResumeState from = sim.resumeState();
  from.stage = Stage::Drape;
  from.previewPositions = from.positions;
  from.previewTime = from.time;
  Scene drapeScene = preview;
  drapeScene.settings.set("solver.stage", "drape", "test");
  Simulation drape(drapeScene, from);
  ASSERT_TRUE(drape.resumed());
  EXPECT_FALSE(drape.finished());
  int steps = 0;
  while (!drape.finished()) {
    EXPECT_EQ(drape.step().stage, Stage::Drape);
    ++steps;
  }
  EXPECT_GT(steps, 0);
  EXPECT_EQ(drape.endReason(), "MaxSimTime");
  EXPECT_NEAR(drape.time(), from.time + 0.04, 0.011);  // the drape's own 0.04 s (its steps grow to 10 ms)
}

}  // namespace
}  // namespace drape::test
