// The placement fit's drape (garment/placement_fit.h): after a short drape GarmentCode's shirt, fitted onto the broad,
// tall mannequin, is less strained than as laid out. The fit itself is checked in tests/unit/garment/placement_fit_test.cpp.
#include <gtest/gtest.h>

#include <utility>

#include "drape/sim/simulation.h"
#include "placement_fit_support.h"
#include "shared_data.h"

namespace drape {
namespace {

// Largest triangle strain after a short Newton drape (2 cm mesh).
double strainAfterShortDrape(Scene scene) {
  scene.settings.set("solver.stage", "drape", "test");
  scene.settings.set("solver.max_sim_time", "0.3", "test");
  Simulation sim(std::move(scene));
  StepReport last;
  while (!sim.finished()) {
    last = sim.step();
    if (last.status == StepStatus::Diverged) break;
  }
  return last.maxStrain;
}

TEST_F(BroadTallBody, ShortDrapeOfTheFittedShirtIsLessStrained) {
  DRAPE_SHARED_FILE(pattern, "garmentcode/shirt_mean_specification.json");
  const double fitted = strainAfterShortDrape(shirt(pattern, true, 0.02));
  const double asLaidOut = strainAfterShortDrape(shirt(pattern, false, 0.02));
  EXPECT_LT(fitted, asLaidOut);
}

}  // namespace
}  // namespace drape
