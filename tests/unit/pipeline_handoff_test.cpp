// The preview -> drape hand-off of the full pipeline: when the preview hands over (hand-off speed held for 0.1 s,
// or its time limit), how the drape starts from the preview's state (no second initial relaxation unless asked
// for), and when the preview is given up for a drape from the placed garment (solver.preview.failure_strain). The
// hand-offs of whole library drapes are slow tests (tests/slow/pipeline_handoff_drape_test.cpp).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>

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

// Stretch of triangle t (largest singular value of its deformation gradient, minus 1) from the garment's rest
// coordinates (metres) to positions x, computed here from the two edge vectors.
double stretchOf(const Garment& g, const Eigen::MatrixX3d& x, int t) {
  const int a = g.triangles(t, 0), b = g.triangles(t, 1), c = g.triangles(t, 2);
  Eigen::Matrix2d rest;
  rest.col(0) = (g.rest.row(b) - g.rest.row(a)).transpose();
  rest.col(1) = (g.rest.row(c) - g.rest.row(a)).transpose();
  Eigen::Matrix<double, 3, 2> now;
  now.col(0) = (x.row(b) - x.row(a)).transpose();
  now.col(1) = (x.row(c) - x.row(a)).transpose();
  const Eigen::Matrix<double, 3, 2> f = now * rest.inverse();
  const Eigen::Matrix2d c2 = f.transpose() * f;  // right Cauchy-Green tensor: its larger eigenvalue, closed form
  const double mean = 0.5 * c2.trace(), half = 0.5 * (c2(0, 0) - c2(1, 1));
  const double gap = std::sqrt(half * half + c2(0, 1) * c2(0, 1));
  return std::sqrt(mean + gap) - 1.0;
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
  // Every speed is below 100 m/s: the hand-off comes after the 0.1 s window, which opens once the preview's
  // quasi-static start is over, long before the 0.5 s limit. (The tablecloth's cotton is stiff for this mesh and
  // step: a softened preview would hand over at softened_max_time, stiff_fabric_preview_test.cpp. Not softened
  // here.)
  const std::pair<std::string, std::string> ownStiffness{"solver.preview.pipeline_courant_limit", "0"};
  Simulation eager(coarseTablecloth({{"solver.preview.handoff_speed", "100"}, ownStiffness}));
  const double relaxation = eager.scene().settings.number("solver.preview.relaxation_time");
  double handoff = 0.0;
  firstDrapeStep(eager, &handoff);
  EXPECT_GE(handoff, relaxation + 0.1 - 1e-9);
  EXPECT_LT(handoff, relaxation + 0.15);
  // A relaxing cloth moves at most g h (0.08 m/s at 1/120 s) whatever its forces: no window opens before the
  // relaxation ends (otherwise this one would hand over at 0.1 s, halfway through its relaxation).
  Simulation relaxing(coarseTablecloth(
      {{"solver.preview.handoff_speed", "100"}, {"solver.preview.relaxation_time", "0.2"}, ownStiffness}));
  firstDrapeStep(relaxing, &handoff);
  EXPECT_GE(handoff, 0.3 - 1e-9);
  EXPECT_LT(handoff, 0.35);
  // No speed is below 0: the preview runs to its time limit.
  Simulation never(
      coarseTablecloth({{"solver.preview.handoff_speed", "0"}, {"solver.preview.max_time", "0.3"}, ownStiffness}));
  firstDrapeStep(never, &handoff);
  EXPECT_GE(handoff, 0.3 - 1e-9);
  EXPECT_LT(handoff, 0.32);
}

// The coarse assembly (solver.preview.assembly_edge_length) has solver.preview.max_time from the start; the garment's
// own mesh, carried over from it, gets max_time again for its own settling: handed over soon after its own mesh is
// sewn, the garment is still moving and the drape takes longer.
TEST(PipelineHandoff, OwnMeshGetsThePreviewTimeAgainAfterTheCoarseAssembly) {
  Simulation sim(libraryScene("default.json", {{"solver.stage", "full"},
                                               {"mesh.target_edge_length", "0.02"},
                                               {"solver.preview.assembly_edge_length", "0.035"},
                                               {"solver.preview.handoff_speed", "0"},
                                               {"solver.preview.max_time", "0.35"}}));
  ASSERT_TRUE(sim.assembling());
  while (sim.assembling() && !sim.finished()) ASSERT_NE(sim.step().status, StepStatus::Diverged);
  const double carried = sim.time();
  ASSERT_EQ(sim.stage(), Stage::Preview) << "the coarse assembly was not sewn within max_time: t = " << carried;
  double handoff = 0.0;
  firstDrapeStep(sim, &handoff);
  std::printf("[ PipelineHandoff ] carried over to the own mesh at %.3f s, drape from %.3f s\n", carried, handoff);
  EXPECT_GE(handoff, carried + 0.35 - 1e-9);
  EXPECT_LT(handoff, carried + 0.36);
}

TEST(PipelineHandoff, RelaxingPreviewIsNotSettledByItsZeroedVelocities) {
  // While the preview relaxes it zeroes the velocities after every step, but the cloth still falls h^2 g per
  // step (h g = 0.08 m/s at h = 1/120 s, above the 0.01 m/s rest speed): the settle test reads the step's motion.
  Simulation sim(coarseTablecloth({{"solver.stage", "preview"}, {"solver.preview.relaxation_time", "0.3"}}));
  StepReport last;
  while (sim.time() < 0.25 && !sim.finished()) last = sim.step();
  EXPECT_FALSE(sim.finished()) << "settled at t = " << sim.time() << " s while relaxing";
  EXPECT_GT(last.kineticEnergy, 0.0);
}

TEST(PipelineHandoff, TornPreviewIsGivenUpForTheDrapeFromThePlacedGarment) {
  // The first preview step of the default scene stretches a triangle along the closing seams by about 300 %: with a
  // failure strain of 200 % and no quasi-static start, that counts as a tear, and the drape starts from the placed
  // garment at scene time 0 (with its initial relaxation), not from the preview's state.
  // (Without the restart with free contact targets, stiff_fabric_preview_test.cpp, which would tear again.)
  Simulation sim(libraryScene("default.json", {{"solver.stage", "full"},
                                               {"solver.preview.failure_strain", "2"},
                                               {"solver.preview.relaxation_time", "0"},
                                               {"solver.preview.retry_without_held_targets", "false"}}));
  const Eigen::MatrixX3d placed = sim.positions();
  const StepReport first = sim.step();
  EXPECT_EQ(first.stage, Stage::Preview);
  ASSERT_GT(first.maxStrain, 2.0);
  EXPECT_EQ(sim.stage(), Stage::Drape);
  EXPECT_NE(sim.previewFailure().find("the drape starts from the placed garment"), std::string::npos);
  EXPECT_DOUBLE_EQ(sim.time(), 0.0);
  EXPECT_EQ((sim.positions() - placed).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(sim.resumeState().previewPositions.rows(), 0);
  EXPECT_DOUBLE_EQ(sim.step().h, sim.scene().settings.number("solver.newton.h_max") / 16.0);

  // At the default (500 %) the same step does not fail: the preview goes on.
  Simulation kept(libraryScene("default.json", {{"solver.stage", "full"}}));
  kept.step();
  EXPECT_EQ(kept.stage(), Stage::Preview);
  EXPECT_TRUE(kept.previewFailure().empty());

  // With the default quasi-static start (0.05 s), the same overshoot falls inside it and is not counted either: the
  // seams' first closing may overshoot there and recover (docs/ENGINE.md, "Design notes").
  Simulation relaxing(libraryScene("default.json", {{"solver.stage", "full"}, {"solver.preview.failure_strain", "2"}}));
  const StepReport overshoot = relaxing.step();
  ASSERT_GT(overshoot.maxStrain, 2.0);
  ASSERT_LT(overshoot.time, relaxing.scene().settings.number("solver.preview.relaxation_time"));
  EXPECT_EQ(relaxing.stage(), Stage::Preview);
  EXPECT_TRUE(relaxing.previewFailure().empty());
}

TEST(PipelineHandoff, TornPreviewAloneGoesOnAndSaysItsResultIsWrong) {
  // The same torn first step, in a preview run on its own (the GUI's Preview, drape --simulate --solver preview):
  // nothing to fall back to, so the preview goes on, and previewFailure() says from that step on, once, that its
  // result is wrong.
  Simulation sim(libraryScene("default.json", {{"solver.stage", "preview"},
                                               {"solver.preview.failure_strain", "2"},
                                               {"solver.preview.relaxation_time", "0"},
                                               {"solver.preview.retry_without_held_targets", "false"}}));
  ASSERT_TRUE(sim.previewFailure().empty());
  const StepReport first = sim.step();
  ASSERT_GT(first.maxStrain, 2.0);
  EXPECT_EQ(sim.stage(), Stage::Preview);
  EXPECT_GT(sim.time(), 0.0);
  const std::string said = sim.previewFailure();
  // It says where: the most stretched triangle (checked against every triangle's stretch computed here), its panel
  // and its centre.
  const Garment& garment = sim.garment();
  const Eigen::MatrixX3d x = sim.positions();
  const int t = first.maxStrainTriangle;
  ASSERT_GE(t, 0);
  EXPECT_NEAR(stretchOf(garment, x, t), first.maxStrain, 1e-9);
  for (int other = 0; other < garment.triangles.rows(); ++other)
    ASSERT_LE(stretchOf(garment, x, other), first.maxStrain + 1e-9) << "triangle " << other;
  const std::string panel = garment.panelNames[garment.trianglePanel[t]];
  EXPECT_NE(said.find("triangle " + std::to_string(t) + " of panel " + panel + ","), std::string::npos) << said;
  char y[32];
  std::snprintf(y, sizeof y, "y %.3f,",
                (x(garment.triangles(t, 0), 1) + x(garment.triangles(t, 1), 1) + x(garment.triangles(t, 2), 1)) / 3.0);
  EXPECT_NE(said.find(y), std::string::npos) << said;
  EXPECT_NE(said.find("only the drape's can be trusted"), std::string::npos) << said;
  EXPECT_EQ(said.find("the drape starts from the placed garment"), std::string::npos) << said;
  // Later steps (torn or not) keep the first step's message.
  sim.step();
  EXPECT_EQ(sim.stage(), Stage::Preview);
  EXPECT_EQ(sim.previewFailure(), said);
}

TEST(PipelineHandoff, DrapeAskedToStartFromATornPreviewStateStartsFromThePlacedGarment) {
  // What the GUI's Drape button (and an edit during a drape) hands over: a preview state to start the drape from.
  Simulation preview(coarseTablecloth({{"solver.stage", "preview"}}));
  for (int i = 0; i < 5; ++i) preview.step();
  ResumeState from = preview.resumeState();
  from.stage = Stage::Drape;
  from.previewPositions = from.positions;
  from.previewTime = from.time;
  Scene scene = coarseTablecloth({{"solver.stage", "drape"}});
  const Eigen::MatrixX3d placed = Simulation(scene).positions();

  Simulation intact(scene, from);
  EXPECT_TRUE(intact.resumed());
  EXPECT_TRUE(intact.previewFailure().empty());
  EXPECT_DOUBLE_EQ(intact.time(), from.time);

  // One vertex 2 m away stretches its triangles far past 500 %.
  from.previewPositions(0, 1) += 2.0;
  Simulation torn(scene, from);
  EXPECT_FALSE(torn.resumed());
  EXPECT_NE(torn.previewFailure().find("the drape starts from the placed garment"), std::string::npos);
  EXPECT_DOUBLE_EQ(torn.time(), 0.0);
  EXPECT_EQ((torn.positions() - placed).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace
}  // namespace drape::test
