#include <gtest/gtest.h>

#include "drape/core/input_error.h"
#include "drape/fabric/fabric.h"
#include "shared_data.h"

namespace drape {
namespace {

TEST(Fabric, EveryPresetLoadsWithRealisticMagnitudes) {
  const auto names = fabricPresetNames(test::assetsDir() / "fabrics");
  ASSERT_GE(names.size(), 6u);
  for (const auto& name : names) {
    const Fabric f = loadFabricPreset(name, test::assetsDir() / "fabrics");
    // DESIGN.md section 4: stretch 1e2-1e4 N/m (heavy denim a little above), bending 1e-7-1e-4 N m,
    // density 0.05-0.5 kg/m^2.
    EXPECT_GE(f.stretchWeft, 1e2) << name;
    EXPECT_LE(f.stretchWarp, 3e4) << name;
    EXPECT_GE(f.bendWeft, 1e-7) << name;
    EXPECT_LE(f.bendWarp, 1e-4) << name;
    EXPECT_GE(f.density, 0.04) << name;
    EXPECT_LE(f.density, 0.5) << name;
  }
}

TEST(Fabric, DenimIsStifferAndHeavierThanSilk) {
  const auto dir = test::assetsDir() / "fabrics";
  const Fabric denim = loadFabricPreset("denim", dir), silk = loadFabricPreset("silk_charmeuse", dir);
  EXPECT_GT(denim.bendWarp, 10 * silk.bendWarp);
  EXPECT_GT(denim.density, 3 * silk.density);
}

TEST(Fabric, UnknownPresetListsAvailable) {
  try {
    loadFabricPreset("velvet", test::assetsDir() / "fabrics");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("jersey_knit"), std::string::npos);
  }
}

}  // namespace
}  // namespace drape
