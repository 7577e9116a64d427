// Real garments drawn as a designer sees them: GarmentCode's shirt placed on the body it was made for, seen from
// the back (its back panels are wound the other way in the file and must still show their outside). Finished drapes
// in which no patch of body shows through the cloth from the front or the back are slow tests
// (tests/slow/body_through_cloth_test.cpp).
#include <gtest/gtest.h>

#include "body_through_cloth_support.h"
#include "drape/scene/scene.h"
#include "drape/sim/scene_garment.h"
#include "drape/sim/snapshot_builder.h"
#include "golden_support.h"
#include "render_fixture.h"
#include "shared_data.h"

namespace drape::test {
namespace {

TEST_F(RenderTest, GarmentCodeShirtPlacedFromTheBackShowsItsOutside) {
  DRAPE_SHARED_FILE(pattern, "garmentcode/shirt_mean_specification.json");
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  const Scene scene = sceneOf(pattern, body, "none");
  const Garment garment = buildSceneGarment(scene, nullptr);
  const Snapshot snapshot = makeSnapshot(scene, garment, garment.positions);
  render::RenderOptions o = smallOptions();
  EXPECT_TRUE(matchesGolden(renderer().render(snapshot, render::ViewPreset::Back, o), "gc_shirt_placed_back"));
}

}  // namespace
}  // namespace drape::test
