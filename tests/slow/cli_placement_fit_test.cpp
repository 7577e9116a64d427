// placement.fit through the executable: on a mannequin made with --make-avatar from measurements 15 % broader at the
// shoulders and 10 % taller, the GarmentCode shirt's panels are moved and named in warnings. A pattern laid out for its
// avatar is checked in tests/cli/cli_placement_test.cpp.
#include <gtest/gtest.h>

#include <string>

#include "cli_placement_support.h"
#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

TEST(CliPlacement, ShirtOnABroaderTallerMannequinIsMovedWithAWarningPerPanel) {
  DRAPE_SHARED_FILE(shirt, "garmentcode/shirt_mean_specification.json");
  const auto made = drape("--make-avatar " + quote((testDataDir() / "bodies" / "broad_tall.yaml").string()) + " -o " +
                          path("broad_tall.obj"));
  ASSERT_EQ(made.exitCode, 0) << made.err;
  const std::string common = "--simulate " + quote(shirt.string()) + " --avatar " + path("broad_tall.obj") +
                             " --set mesh.target_edge_length=0.03 --solver none ";
  const auto fitted = drape(common + "-o " + path("shirt_fitted.obj"));
  ASSERT_EQ(fitted.exitCode, 0) << fitted.err;
  for (const char* panel : {"left_sleeve_f", "right_sleeve_b", "left_ftorso"})
    EXPECT_NE(fitted.out.find("shirt_mean_specification.json: placement: panel '" + std::string(panel) + "' moved"),
              std::string::npos)
        << panel << "\n"
        << fitted.out;
  const auto asLaidOut = drape(common + "--set placement.fit=false -o " + path("shirt_as_laid_out.obj"));
  ASSERT_EQ(asLaidOut.exitCode, 0) << asLaidOut.err;
  EXPECT_EQ(asLaidOut.out.find("placement: panel"), std::string::npos);
  // The torso went up to the taller body's shoulders: more than 10 cm.
  const auto a = objVertices(kScratch / "shirt_fitted.obj"), b = objVertices(kScratch / "shirt_as_laid_out.obj");
  ASSERT_EQ(a.size(), b.size());
  EXPECT_GT(maxDistance(a, b), 0.10);
}

}  // namespace
}  // namespace drape::test
