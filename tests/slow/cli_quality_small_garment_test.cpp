// The quality verdict through the executable on a garment far too small for the body: it fails with exit status 4 and
// a "warning: quality:" line per failed check, and the reported stretch is checked against one computed from the OBJ.
// The verdict's other tests are in tests/cli/cli_quality_test.cpp.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_quality_support.h"
#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

TEST(CliQuality, GarmentTooSmallForTheBodyFailsTheVerdictWithExitStatus4) {
  // The library t-shirt with every panel scaled to 60 % (tests/data/scenes/tshirt_60_percent.json), drape at 2 cm.
  const auto obj = kScratch / "small.obj", stats = kScratch / "small.json";
  auto r = drape("--simulate " + quote((testDataDir() / "scenes" / "tshirt_60_percent.json").string()) +
                 " --solver drape -o " + quote(obj.string()) + " --stats " + quote(stats.string()));
  ASSERT_EQ(r.exitCode, 4) << r.err << r.out;
  EXPECT_NE(r.out.find("warning: quality: max_strain: a triangle stretched"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(readWhole(stats));
  const auto& quality = j.at("quality");
  EXPECT_FALSE(quality.at("passed").get<bool>());
  const auto& strain = quality.at("checks").at("max_strain");
  EXPECT_FALSE(strain.at("passed").get<bool>());
  EXPECT_GT(strain.at("value").get<double>(), strain.at("threshold").get<double>());
  EXPECT_GE(strain.at("triangle").get<int>(), 0);
  EXPECT_LT(strain.at("triangle").get<int>(), j.at("triangles").get<int>());
  // The stretch the verdict reports is the written garment's, computed here from its OBJ.
  EXPECT_NEAR(strain.at("value").get<double>(), maxStretchOfObj(obj), 1e-5 * (1.0 + maxStretchOfObj(obj)));
  // One warning line per failed check, each naming its check.
  int failed = 0;
  for (const auto& [name, check] : quality.at("checks").items())
    if (!check.at("passed").get<bool>()) {
      ++failed;
      EXPECT_NE(r.out.find("warning: quality: " + name + ":"), std::string::npos) << name << "\n" << r.out;
    }
  EXPECT_EQ(countLines(r.out, "warning: quality: "), failed) << r.out;
  // The collider checks are there: the scene has an avatar.
  EXPECT_TRUE(quality.at("checks").contains("penetration_depth"));
  EXPECT_TRUE(quality.at("checks").at("penetration_depth").contains("vertex"));
}

}  // namespace
}  // namespace drape::test
