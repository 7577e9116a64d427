// The quality verdict through the executable: a garment far too small for the body fails it with exit status 4 and
// a "warning: quality:" line per failed check, a hanging cloth at rest passes it, and --render --simulate of a drape
// cut short fails it on the rest requirement. The reported stretch is checked against one computed from the OBJ.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

const std::filesystem::path kScratch = testOutputDir() / "cli_quality";

ProcessResult drape(const std::string& args) {
  return runProcess(quote(DRAPE_EXECUTABLE) + " " + args + " </dev/null", kScratch);
}

std::string asset(const std::string& relative) {
  return quote((assetsDir() / relative).string());
}

// The largest principal stretch minus one over the faces of an OBJ written by drape: v (metres), vt (the pattern
// coordinates, metres) and f a/a/a lines, from the singular values of each face's deformation gradient.
double maxStretchOfObj(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector2d> vt;
  double best = -1.0;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string tag;
    ss >> tag;
    if (tag == "v") {
      Eigen::Vector3d p;
      ss >> p.x() >> p.y() >> p.z();
      v.push_back(p);
    } else if (tag == "vt") {
      Eigen::Vector2d p;
      ss >> p.x() >> p.y();
      vt.push_back(p);
    } else if (tag == "f") {
      int idx[3];
      for (int& k : idx) {
        std::string corner;
        ss >> corner;
        k = std::stoi(corner.substr(0, corner.find('/'))) - 1;
      }
      Eigen::Matrix2d dm;
      dm << vt[idx[1]] - vt[idx[0]], vt[idx[2]] - vt[idx[0]];
      Eigen::Matrix<double, 3, 2> ds;
      ds << v[idx[1]] - v[idx[0]], v[idx[2]] - v[idx[0]];
      const Eigen::Matrix<double, 3, 2> f = ds * dm.inverse();
      best = std::max(best, Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>>(f).singularValues()(0) - 1.0);
    }
  }
  return best;
}

int countLines(const std::string& text, const std::string& prefix) {
  int n = 0;
  for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1))
    n += at == 0 || text[at - 1] == '\n';
  return n;
}

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
  // The default t-shirt with the softest stretch the settings admit, no shear or bending stiffness, 1000 m/s^2 and
  // 0.1 s steps: a triangle stretches past what any fabric holds. The run ends Diverged (exit 3), the line and the
  // stats name the triangle, and the OBJ holds the state before it (its stretch computed here from the OBJ).
  const auto obj = kScratch / "exploded.obj", stats = kScratch / "exploded.json";
  auto r = drape("--simulate " + asset("scenes/default.json") +
                 " --solver drape --set fabric.stretch_warp=1e-3 --set fabric.stretch_weft=1e-3 --set fabric.shear=0"
                 " --set fabric.bend_warp=0 --set fabric.bend_weft=0 --set sim.gravity=-1000"
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
