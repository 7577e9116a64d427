// The full pipeline on GarmentCode's shirt in denim on mean_all (../shared/data, 1 cm mesh): its held preview tears
// the back panel at the shoulder, starts over with the avatar contact targets free
// (solver.preview.retry_without_held_targets) and hands over whole (docs/ENGINE.md, "Design notes"). The cotton
// shirt's pipeline is in tests/unit/real_garment_pipeline_test.cpp.
#include <gtest/gtest.h>

#include <string>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "real_garment_pipeline_support.h"
#include "shared_data.h"

namespace drape::test {
namespace {

// In denim the held preview tears the back panel at the shoulder: it starts over with its contact targets free and
// hands over whole.
TEST(RealGarmentPipeline, GarmentCodeDenimShirtTornPreviewStartsOverWithTargetsFree) {
  DRAPE_SHARED_FILE(shirt, "garmentcode/shirt_mean_specification.json");
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  Simulation sim(shirtOnMeanAll({{"fabric.preset", "denim"}}));
  StepReport last;
  while (sim.previewRestarts() == 0 && sim.stage() == Stage::Preview && sim.time() < 0.2) last = sim.step();
  ASSERT_EQ(sim.previewRestarts(), 1) << "handed over at " << 100.0 * last.maxStrain << " %";
  EXPECT_GT(last.maxStrain, sim.scene().settings.number("solver.preview.failure_strain"));
  EXPECT_NE(sim.previewRestartReasons()[0].find("with its contact targets not held"), std::string::npos)
      << sim.previewRestartReasons()[0];
  EXPECT_TRUE(sim.previewTargetsFreed());
  EXPECT_EQ(sim.stage(), Stage::Preview);
  EXPECT_DOUBLE_EQ(sim.time(), 0.0);
  while (sim.stage() == Stage::Preview) last = sim.step();
  EXPECT_EQ(sim.previewRestarts(), 1);
  EXPECT_LT(last.maxStrain, 1.0) << "handed over stretched";  // freed: 50 %
  EXPECT_TRUE(sim.previewFailure().empty()) << sim.previewFailure();
  EXPECT_EQ(sim.previewRecoveries().size(), 1u);
  EXPECT_EQ(sim.resumeState().previewPositions.rows(), sim.garment().vertexCount());
}

}  // namespace
}  // namespace drape::test
