// Real garments draped from their placed panels on a coarse mesh (4 cm edges), each tens of seconds in Release:
// GarmentCode's pencil dress (../shared/data/garmentcode) on Drape's generated female mannequin, and
// Garment-Pattern-Generator's skirt moved onto GarmentCode's mean_all body by its scene's placement.translate. The
// checks are those of real_garment_drape_support.h; the shirts' drapes are in tests/unit/newton/real_garment_drape_test.cpp.
#include <gtest/gtest.h>

#include <string>

#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "real_garment_drape_support.h"
#include "shared_data.h"

namespace drape {
namespace {

TEST(RealGarmentDrape, PencilDressOnGeneratedFemaleMannequin) {
  DRAPE_SHARED_FILE(dress, "garmentcode/dress_pencil_specification.json");
  const DrapeOutcome o = drape(dress, test::assetsDir() / "avatars/female.obj", 0.04, 0.4);
  expectHangsOnTorso(o, femaleLevels());
}

// Garment-Pattern-Generator places its panels around a body whose origin is at the hips; mean_all stands on the
// floor. Placed as the file says, the skirt lies below the feet, the scene says so, and it would fall forever; the
// test scene's placement.translate (1.15 m up) puts its waist at mean_all's, where it drapes to rest.
TEST(RealGarmentDrape, GarmentPatternGeneratorSkirtMovedOntoMeanAllHangsFromTheWaist) {
  DRAPE_SHARED_FILE(skirt, "garment-pattern-generator/skirt_2_panels.json");
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  DRAPE_SHARED_FILE(measurements, "garmentcode/mean_all.yaml");
  const MannequinLevels levels = mannequinLevels(loadBodyMeasurements(measurements));
  SceneRequest request;
  request.input = test::testDataDir() / "scenes" / "gpg_skirt_2_panels_on_mean_all.json";
  auto placementWarnings = [](const Scene& scene) {
    int n = 0;
    for (const std::string& w : scene.diagnostics.warnings()) n += w.find("placement.translate") != std::string::npos;
    return n;
  };
  {
    SceneRequest asInTheFile = request;
    // With placement.fit off: the fit alone would lift the skirt to the waist (placement_fit_test.cpp).
    asInTheFile.overrides = {
        {"placement.translate", "0,0,0"}, {"placement.fit", "false"}, {"mesh.target_edge_length", "0.04"}};
    const Simulation placed(loadScene(asInTheFile));
    EXPECT_EQ(placementWarnings(placed.scene()), 1);
    EXPECT_LT(placed.positions().col(1).maxCoeff(), 0.0) << "the skirt as the file places it is below the feet";
  }
  const Simulation moved(loadScene(request));
  EXPECT_EQ(placementWarnings(moved.scene()), 0);

  // At rest after about 3.1 s: the stiff contact band lets the loose skirt creep on the hips for a while.
  const DrapeOutcome o = drape(request, 0.04, 4.0);
  EXPECT_FALSE(o.diverged);
  EXPECT_TRUE(o.atRest) << "no early stop within " << o.simTime << " s";
  EXPECT_LE(o.maxPenetration, o.contactThickness) << "a garment vertex ended inside the body";
  EXPECT_LT(o.maxStitchGap, 0.01) << "a seam did not close";
  EXPECT_NEAR(o.topY, levels.waist, 0.05) << "the skirt does not hang from the waist";
  EXPECT_LT(o.centroidY, levels.waist);
  EXPECT_GT(o.centroidY, levels.crotch - 0.15);
}

}  // namespace
}  // namespace drape
