// drape --bench --levels and drape --trade-levels through the executable: every candidate of
// assets/trade/level_candidates.json is run against a reference on the finest candidate mesh, and the levels file
// keeps exactly the candidates that no other beats on both wall time and distance, fastest first.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "cli_solver_support.h"
#include "run_process.h"

namespace drape::test {
namespace {

TEST(CliTrade, LevelsRunEveryCandidateAndTradeLevelsKeepsTheFront) {
  const auto report = kScratch / "levels_report.json", levels = kScratch / "levels.json";
  const std::string patch = quote((testDataDir() / "patterns" / "circle_patch.json").string());
  // Meshed at 2 cm, so that the candidates' finest mesh (1 cm) is the reference's.
  auto r = drape("--bench " + patch + " --set mesh.target_edge_length=0.02 --max-sim-time 0.005 --levels -o " +
                 quote(report.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const auto candidates = nlohmann::json::parse(readWhole(assetsDir() / "trade" / "level_candidates.json"));
  const auto j = nlohmann::json::parse(readWhole(report));
  std::string finest;
  std::map<std::string, std::pair<double, double>> measured;  // level -> (wall s, mean mm)
  for (const auto& c : candidates.at("levels")) {
    const std::string name = c.at("name");
    const std::string mesh = c.at("settings").at("mesh.target_edge_length");
    if (finest.empty() || std::stod(mesh) < std::stod(finest)) finest = mesh;
    bool found = false;
    for (const auto& run : j.at("runs"))
      if (run.at("level") == name) {
        found = true;
        EXPECT_EQ(run.at("settings"), c.at("settings")) << name;
        measured[name] = {run.at("wall_time_s").get<double>(), run.at("mean_distance_mm").get<double>()};
      }
    EXPECT_TRUE(found) << name;
  }
  EXPECT_EQ(j.at("reference").at("settings").at("mesh.target_edge_length"), finest) << j.at("reference");

  auto g = drape("--trade-levels " + quote(report.string()) + " -o " + quote(levels.string()));
  ASSERT_EQ(g.exitCode, 0) << g.err << g.out;
  const auto l = nlohmann::json::parse(readWhole(levels));
  EXPECT_EQ(l.at("levels").size() + l.at("dropped").size(), measured.size());
  double lastWall = 0.0;
  for (const auto& level : l.at("levels")) {
    const std::string name = level.at("name");
    ASSERT_TRUE(measured.count(name)) << name;
    const auto [wall, mm] = measured[name];
    EXPECT_GE(wall, lastWall) << name << ": fastest first";
    lastWall = wall;
    for (const auto& [other, cost] : measured)
      EXPECT_FALSE(cost.first <= wall && cost.second <= mm && (cost.first < wall || cost.second < mm))
          << name << " is kept although " << other << " beats it";
    EXPECT_NE(level.at("summary").get<std::string>().find(" mm from the reference"), std::string::npos);
  }
  for (const auto& d : l.at("dropped")) {
    const auto [wall, mm] = measured[d.at("name")];
    const auto [byWall, byMm] = measured[d.at("dominated_by")];
    EXPECT_TRUE(byWall <= wall && byMm <= mm) << d;
  }
}

}  // namespace
}  // namespace drape::test
