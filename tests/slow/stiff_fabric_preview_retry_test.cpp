// A torn preview of a fabric stiff for its mesh and step (a Courant number above 5, preview_fabric.h), the default
// t-shirt in cotton shirting at the fabric's own stiffness, starts over once, softer
// (solver.preview.retry_courant_limit): from the placed garment at scene time 0, its fabric softened to the retry's
// Courant number, and stays whole. The other retries and the pipeline's softening are in
// tests/unit/stiff_fabric_preview_test.cpp.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "stiff_fabric_preview_support.h"

namespace drape::test {
namespace {

// Cotton shirting: Courant number about 26 at the default preview step; its preview tears at about 0.051 s
// (docs/BENCHMARKS.md, "Findings worth keeping").
TEST(PreviewRetry, TornCottonPreviewStartsOverSofterFromThePlacedGarmentAndStaysWhole) {
  const Overrides ownStiffness = {{"solver.stage", "full"}, {"solver.preview.pipeline_courant_limit", "0"}};
  Simulation sim(defaultTshirt("cotton_shirting", ownStiffness));
  const Eigen::MatrixX3d placed = sim.positions();
  // The Courant number it reports is the fabric's own, computed from the scene's model.
  EXPECT_GT(sim.previewCourantNumber(), 5.0);
  EXPECT_EQ(sim.previewCourantLimit(), 0.0);
  double tornAt = -1.0;
  while (sim.previewRestarts() == 0 && sim.time() < 0.2) tornAt = sim.step().time;
  ASSERT_EQ(sim.previewRestarts(), 1) << "the cotton preview did not tear by 0.2 s";
  EXPECT_GT(tornAt, sim.scene().settings.number("solver.preview.relaxation_time"));
  // Started over: the preview again, at time 0, from the placed garment, softer.
  EXPECT_EQ(sim.stage(), Stage::Preview);
  EXPECT_DOUBLE_EQ(sim.time(), 0.0);
  EXPECT_EQ((sim.positions() - placed).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(sim.previewCourantLimit(), 5.0);
  ASSERT_EQ(sim.previewRestartReasons().size(), 1u);
  const std::string said = sim.previewRestartReasons()[0];
  EXPECT_TRUE(sim.previewFailure().empty()) << sim.previewFailure();  // started over: not a failure
  EXPECT_TRUE(contains(said, "starts over from the placed garment")) << said;
  EXPECT_TRUE(contains(said, " to 5 (solver.preview.retry_courant_limit)")) << said;
  EXPECT_FALSE(contains(said, "the drape starts")) << said;
  EXPECT_FALSE(contains(said, "--set solver.preview.courant_limit")) << said;  // no hint: it is done already
  // The same preview the scene would run with courant_limit 5 from the start: its first step lands where that one's
  // does.
  Overrides soft = ownStiffness;
  soft.emplace_back("solver.preview.courant_limit", "5");
  Simulation softFromStart(defaultTshirt("cotton_shirting", soft));
  EXPECT_LT((sim.positions() - softFromStart.positions()).cwiseAbs().maxCoeff(), 1e-15);
  const StepReport a = sim.step(), b = softFromStart.step();
  EXPECT_DOUBLE_EQ(a.time, b.time);
  EXPECT_LT((sim.positions() - softFromStart.positions()).cwiseAbs().maxCoeff(), 1e-12);
  // An edit that resumes it keeps it soft (the scene still says courant_limit 0).
  const ResumeState from = sim.resumeState();
  EXPECT_EQ(from.previewCourantLimit, 5.0);
  Simulation edited(defaultTshirt("cotton_shirting", ownStiffness), from);
  ASSERT_TRUE(edited.resumed());
  EXPECT_EQ(edited.previewCourantLimit(), 5.0);
  // The softened preview stays whole past the time the stiff one tore, does not start over again, and, softened,
  // hands over to the drape at softened_max_time, from its own state.
  StepReport last;
  while (sim.stage() == Stage::Preview) last = sim.step();
  const double softenedMaxTime = sim.scene().settings.number("solver.preview.softened_max_time");
  ASSERT_GT(softenedMaxTime, tornAt);
  EXPECT_EQ(sim.previewRestarts(), 1);
  EXPECT_TRUE(sim.previewFailure().empty()) << sim.previewFailure();
  EXPECT_EQ(sim.previewRecoveries(), std::vector<std::string>{said});  // recovered from the one tear
  EXPECT_GE(last.time, softenedMaxTime - 1e-12);
  EXPECT_LT(last.time, softenedMaxTime + last.h + 1e-12);
  EXPECT_LT(last.maxStrain, 1.0);  // the torn one: 580 %
  EXPECT_EQ(sim.resumeState().previewPositions.rows(), sim.garment().vertexCount());
}

}  // namespace
}  // namespace drape::test
