// A torn preview with a stiff fabric starts over once, softer (solver.preview.retry_courant_limit): from the placed
// garment at scene time 0, its fabric softened to the retry's Courant number, and a tear after that is given up as
// before (the drape from the placed garment; a preview alone goes on and says its result is wrong).
#include <gtest/gtest.h>

#include <string>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

using Overrides = std::vector<std::pair<std::string, std::string>>;

// The default scene's t-shirt in `fabric` (a preset), settings overridden.
Scene defaultTshirt(const char* fabric, Overrides overrides) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "default.json";
  request.fabricPreset = fabric;
  request.overrides = std::move(overrides);
  return loadScene(request);
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Cotton shirting: Courant number about 26 at the default preview step; its preview tears at about 0.051 s
// (docs/BENCHMARKS.md, stop 36).
TEST(PreviewRetry, TornCottonPreviewStartsOverSofterFromThePlacedGarmentAndStaysWhole) {
  Simulation sim(defaultTshirt("cotton_shirting", {{"solver.stage", "full"}}));
  const Eigen::MatrixX3d placed = sim.positions();
  // The Courant number it reports is the fabric's own, computed from the scene's model.
  EXPECT_GT(sim.previewCourantNumber(), 5.0);
  EXPECT_EQ(sim.previewCourantLimit(), 0.0);
  double tornAt = -1.0;
  while (sim.previewRestarts() == 0 && sim.time() < 0.2) tornAt = sim.step().time;
  ASSERT_EQ(sim.previewRestarts(), 1) << "the cotton preview did not tear by 0.2 s";
  EXPECT_GT(tornAt, sim.scene().settings.number("solver.preview.relaxation_time"));
  // Started over: the preview again, at time 0, from the placed garment, softer.
  EXPECT_EQ(sim.stage(), "preview");
  EXPECT_DOUBLE_EQ(sim.time(), 0.0);
  EXPECT_EQ((sim.positions() - placed).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(sim.previewCourantLimit(), 5.0);
  const std::string said = sim.previewFailure();
  EXPECT_TRUE(contains(said, "starts over from the placed garment")) << said;
  EXPECT_TRUE(contains(said, " to 5 (solver.preview.retry_courant_limit)")) << said;
  EXPECT_FALSE(contains(said, "the drape starts")) << said;
  EXPECT_FALSE(contains(said, "--set solver.preview.courant_limit")) << said;  // no hint: it is done already
  // The same preview the scene would run with courant_limit 5 from the start: its first step lands where that one's
  // does.
  Simulation softFromStart(
      defaultTshirt("cotton_shirting", {{"solver.stage", "full"}, {"solver.preview.courant_limit", "5"}}));
  EXPECT_LT((sim.positions() - softFromStart.positions()).cwiseAbs().maxCoeff(), 1e-15);
  const StepReport a = sim.step(), b = softFromStart.step();
  EXPECT_DOUBLE_EQ(a.time, b.time);
  EXPECT_LT((sim.positions() - softFromStart.positions()).cwiseAbs().maxCoeff(), 1e-12);
  // An edit that resumes it keeps it soft (the scene still says courant_limit 0).
  const ResumeState from = sim.resumeState();
  EXPECT_EQ(from.previewCourantLimit, 5.0);
  Simulation edited(defaultTshirt("cotton_shirting", {{"solver.stage", "full"}}), from);
  ASSERT_TRUE(edited.resumed());
  EXPECT_EQ(edited.previewCourantLimit(), 5.0);
  // The softened preview stays whole past the time the stiff one tore, and does not start over again.
  StepReport last;
  while (sim.stage() == "preview" && sim.time() < tornAt + 0.05) last = sim.step();
  EXPECT_EQ(sim.previewRestarts(), 1);
  EXPECT_EQ(sim.previewFailure(), said);
  EXPECT_LT(last.maxStrain, 0.6);
}

TEST(PreviewRetry, ATearAfterTheRetryIsGivenUp) {
  // With a failure strain of 200 % and no quasi-static start, the first step's seam closing (about 300 %) tears the
  // cotton preview, and again after the retry: the full pipeline then drapes from the placed garment.
  const Overrides strict = {
      {"solver.stage", "full"}, {"solver.preview.failure_strain", "2"}, {"solver.preview.relaxation_time", "0"}};
  Simulation sim(defaultTshirt("cotton_shirting", strict));
  const Eigen::MatrixX3d placed = sim.positions();
  sim.step();
  ASSERT_EQ(sim.previewRestarts(), 1);
  EXPECT_EQ(sim.stage(), "preview");
  sim.step();
  EXPECT_EQ(sim.previewRestarts(), 1);
  EXPECT_EQ(sim.stage(), "drape");
  EXPECT_TRUE(contains(sim.previewFailure(), "the drape starts from the placed garment")) << sim.previewFailure();
  EXPECT_DOUBLE_EQ(sim.time(), 0.0);
  EXPECT_EQ((sim.positions() - placed).cwiseAbs().maxCoeff(), 0.0);

  // Preview alone: the second tear is said, once, and the preview goes on.
  Overrides alone = strict;
  alone[0].second = "preview";
  Simulation preview(defaultTshirt("cotton_shirting", alone));
  preview.step();
  ASSERT_EQ(preview.previewRestarts(), 1);
  EXPECT_TRUE(contains(preview.previewFailure(), "starts over")) << preview.previewFailure();
  preview.step();
  const std::string wrong = preview.previewFailure();
  EXPECT_TRUE(contains(wrong, "only the drape's can be trusted")) << wrong;
  preview.step();
  EXPECT_EQ(preview.previewFailure(), wrong);
  EXPECT_EQ(preview.previewRestarts(), 1);
  EXPECT_GT(preview.time(), 0.0);
}

TEST(PreviewRetry, NoRetryWhenOffOrWhenTheFabricIsNotThatStiff) {
  const Overrides strict = {
      {"solver.stage", "full"}, {"solver.preview.failure_strain", "2"}, {"solver.preview.relaxation_time", "0"}};
  // Off: the first tear is given up, and its message suggests the softening.
  Overrides off = strict;
  off.emplace_back("solver.preview.retry_courant_limit", "0");
  Simulation cotton(defaultTshirt("cotton_shirting", off));
  cotton.step();
  EXPECT_EQ(cotton.previewRestarts(), 0);
  EXPECT_EQ(cotton.stage(), "drape");
  EXPECT_TRUE(contains(cotton.previewFailure(), "--set solver.preview.courant_limit=5")) << cotton.previewFailure();
  // Jersey (Courant number about 4.7, below the retry's 5): softening would change nothing, so no retry.
  Simulation jersey(defaultTshirt("jersey_knit", strict));
  ASSERT_LT(jersey.previewCourantNumber(), 5.0);
  jersey.step();
  EXPECT_EQ(jersey.previewRestarts(), 0);
  EXPECT_EQ(jersey.stage(), "drape");
  // Already softened to the retry's number by the scene: nothing softer to retry with.
  Overrides soft = strict;
  soft.emplace_back("solver.preview.courant_limit", "5");
  Simulation softened(defaultTshirt("cotton_shirting", soft));
  softened.step();
  EXPECT_EQ(softened.previewRestarts(), 0);
  EXPECT_EQ(softened.stage(), "drape");
}

}  // namespace
}  // namespace drape::test
