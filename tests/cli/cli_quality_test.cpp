// The quality verdict through the executable: a hanging cloth at rest passes it, --render --simulate of a drape cut
// short fails it on the rest requirement, and an exploded garment ends Diverged. The reported stretch is checked
// against one computed from the OBJ. A garment far too small for the body, which fails it with exit status 4, is a
// slow test (tests/slow/cli_quality_small_garment_test.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_quality_support.h"
#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

std::string asset(const std::string& relative) {
  return quote((assetsDir() / relative).string());
}

TEST(CliQuality, HangingClothAtRestPassesTheVerdict) {
  const auto obj = kScratch / "hang.obj", stats = kScratch / "hang.json";
  auto r = drape("--simulate " + asset("scenes/hanging_cloth.json") + " --set mesh.target_edge_length=0.1 -o " +
                 quote(obj.string()) + " --stats " + quote(stats.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_EQ(r.out.find("warning: quality"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(readWhole(stats));
  EXPECT_EQ(j.at("status"), "AtRest");
  const auto& quality = j.at("quality");
  EXPECT_TRUE(quality.at("passed").get<bool>());
  const auto& checks = quality.at("checks");
  EXPECT_EQ(checks.at("at_rest").at("value").get<double>(), 1.0);
  EXPECT_EQ(checks.at("self_intersections").at("value").get<double>(), 0.0);
  EXPECT_NEAR(checks.at("max_strain").at("value").get<double>(), maxStretchOfObj(obj), 1e-6);
  // No collider, no collider checks.
  EXPECT_FALSE(checks.contains("inside_fraction"));
  EXPECT_FALSE(checks.contains("penetration_depth"));
}

TEST(CliQuality, RenderOfADrapeCutShortFailsOnTheRestRequirement) {
  const std::string args = "--render " + asset("scenes/hanging_cloth.json") +
                           " --set mesh.target_edge_length=0.1 --simulate drape --max-sim-time 0.02 --size 64x64 -o " +
                           quote((kScratch / "short.png").string());
  auto r = drape(args);
  ASSERT_EQ(r.exitCode, 4) << r.err << r.out;
  EXPECT_NE(r.out.find("warning: quality: at_rest: the run ended with MaxSimTime"), std::string::npos) << r.out;
  EXPECT_EQ(countLines(r.out, "warning: quality: "), 1) << r.out;
  EXPECT_TRUE(std::filesystem::exists(kScratch / "short.png"));
  auto lenient = drape(args + " --set quality.require_rest=false");
  EXPECT_EQ(lenient.exitCode, 0) << lenient.err << lenient.out;
  EXPECT_EQ(lenient.out.find("warning: quality"), std::string::npos) << lenient.out;
}

TEST(CliQuality, ExplodedGarmentEndsDivergedWithExitStatus3) {
  // The default t-shirt with the softest stretch the settings admit, no shear or bending stiffness, the most friction
  // (which holds it on the body instead of letting it slide off), 1000 m/s^2 and 0.1 s steps: a triangle stretches
  // past what any fabric holds. The run ends Diverged (exit 3), the line and the stats name the triangle, and the OBJ
  // holds the state before it (its stretch computed here from the OBJ).
  const auto obj = kScratch / "exploded.obj", stats = kScratch / "exploded.json";
  auto r = drape("--simulate " + asset("scenes/default.json") +
                 " --solver drape --set fabric.stretch_warp=1e-3 --set fabric.stretch_weft=1e-3 --set fabric.shear=0"
                 " --set fabric.bend_warp=0 --set fabric.bend_weft=0 --set fabric.friction=5 --set sim.gravity=-1000"
                 " --set solver.newton.h_max=0.1 --max-sim-time 0.5 -o " +
                 quote(obj.string()) + " --stats " + quote(stats.string()));
  ASSERT_EQ(r.exitCode, 3) << r.err << r.out;
  EXPECT_NE(r.out.find("drape: the drape diverged at t="), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(": the garment exploded: triangle "), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(readWhole(stats));
  EXPECT_EQ(j.at("status"), "Diverged");
  EXPECT_NE(j.at("diverged_reason").get<std::string>().find(" of panel '"), std::string::npos);
  EXPECT_GT(j.at("final").at("max_strain").get<double>(), 100.0);
  const double written = maxStretchOfObj(obj);
  EXPECT_GT(written, 1.0);
  EXPECT_LE(written, 100.0);
}

}  // namespace
}  // namespace drape::test
