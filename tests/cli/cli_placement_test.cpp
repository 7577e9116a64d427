// placement.fit through the executable: `--simulate SCENE --solver none` writes the placed garment, which is the
// same with the fit on and off for a pattern laid out for its avatar. The GarmentCode shirt's panels on a mannequin
// made with --make-avatar from measurements 15 % broader at the shoulders and 10 % taller are a slow test
// (tests/slow/cli_placement_fit_test.cpp).
#include <gtest/gtest.h>

#include <string>

#include "cli_placement_support.h"
#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

TEST(CliPlacement, PatternLaidOutForItsAvatarIsPlacedAlikeWithTheFitOnAndOff) {
  const std::string scene = quote((assetsDir() / "scenes" / "tshirt.json").string());
  const auto on = drape("--simulate " + scene + " --solver none -o " + path("fit_on.obj"));
  ASSERT_EQ(on.exitCode, 0) << on.err;
  EXPECT_EQ(on.out.find("placement: panel"), std::string::npos) << on.out;
  const auto off = drape("--simulate " + scene + " --solver none --set placement.fit=false -o " + path("fit_off.obj"));
  ASSERT_EQ(off.exitCode, 0) << off.err;
  const auto a = objVertices(kScratch / "fit_on.obj"), b = objVertices(kScratch / "fit_off.obj");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_FALSE(a.empty());
  EXPECT_LT(maxDistance(a, b), 0.01);
}

}  // namespace
}  // namespace drape::test
