// The speed <-> accuracy levels from trade reports: the sample reports of tests/data/trade (two scenes, four
// candidates, "Wasteful" slower and less accurate than "Fast" on both) give the Pareto front fastest first with the
// reference scene's numbers; bad reports and levels files are refused with a line naming the report or file and the
// level; the committed assets/trade/speed_accuracy_levels.json is what the committed docs/trade/levels reports give.
#include "drape/trade/speed_accuracy_levels.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "drape/core/input_error.h"

namespace drape::trade {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

json readJson(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot open");
  return json::parse(in);
}

std::vector<json> sampleReports() {
  const fs::path dir = fs::path(DRAPE_TEST_DATA_DIR) / "trade";
  return {readJson(dir / "default.json"), readJson(dir / "tshirt.json")};
}

// The run of level in report (a reference to edit), or a failure.
json& runOf(json& report, const std::string& level) {
  for (json& run : report.at("runs"))
    if (run.value("level", "") == level) return run;
  throw std::runtime_error("the sample report has no level " + level);
}

std::vector<std::string> levelNames(const json& levels) {
  std::vector<std::string> names;
  for (const json& l : levels.at("levels")) names.push_back(l.at("name").get<std::string>());
  return names;
}

// The InputError message of levelsFromReports(reports, reference), or "" with a failure when there is none.
std::string refusal(const std::vector<json>& reports, const std::string& reference = "default") {
  try {
    levelsFromReports(reports, reference);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "the reports were accepted";
  return "";
}

std::string contains(const std::string& text, const std::vector<std::string>& parts) {
  for (const std::string& p : parts)
    if (text.find(p) == std::string::npos) return "'" + p + "' missing from: " + text;
  return "";
}

TEST(SpeedAccuracyLevels, KeepsTheParetoFrontFastestFirstAndNamesWhoDominatesTheDropped) {
  const json levels = levelsFromReports(sampleReports(), "default");
  EXPECT_EQ(levels.at("generated_by"), std::string(kLevelsCommand));
  EXPECT_EQ(levels.at("reference_scene"), "default");
  // Totals over both scenes: Fast 10.2 s / 3.2 mm, Balanced 23.4 / 1.23, Wasteful 27 / 4, Accurate 70.4 / 0.42.
  EXPECT_EQ(levelNames(levels), (std::vector<std::string>{"Fast", "Balanced", "Accurate"}));
  ASSERT_EQ(levels.at("dropped").size(), 1u);
  EXPECT_EQ(levels.at("dropped")[0].at("name"), "Wasteful");
  EXPECT_EQ(levels.at("dropped")[0].at("dominated_by"), "Fast");
}

TEST(SpeedAccuracyLevels, EachLevelCarriesTheReferenceScenesNumbersAndEveryScenes) {
  const json levels = levelsFromReports(sampleReports(), "default");
  const json& fast = levels.at("levels")[0];
  EXPECT_EQ(fast.at("settings").at("solver.newton.h_max"), "0.002");
  EXPECT_EQ(fast.at("settings").size(), 4u);
  EXPECT_DOUBLE_EQ(fast.at("wall_time_s").get<double>(), 4.2);
  EXPECT_DOUBLE_EQ(fast.at("mean_distance_mm").get<double>(), 1.2);
  EXPECT_TRUE(fast.at("at_rest").get<bool>());
  EXPECT_EQ(fast.at("summary"), "about 4 s to rest, 1.2 mm from the reference on the default scene");
  EXPECT_DOUBLE_EQ(fast.at("scenes").at("tshirt").at("wall_time_s").get<double>(), 6.0);
  EXPECT_DOUBLE_EQ(fast.at("scenes").at("tshirt").at("mean_distance_mm").get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(fast.at("scenes").at("default").at("wall_time_s").get<double>(), 4.2);
  // Balanced hit its time limit on the default scene.
  const json& balanced = levels.at("levels")[1];
  EXPECT_FALSE(balanced.at("at_rest").get<bool>());
  EXPECT_EQ(balanced.at("summary"),
            "about 9 s (3 s simulated, not at rest), 0.43 mm from the reference on the default scene");
  EXPECT_EQ(levels.at("levels")[2].at("summary"),
            "about 30 s to rest, 0.12 mm from the reference on the default scene");

  // The same front from the other scene's point of view, with its numbers.
  const json fromTshirt = levelsFromReports(sampleReports(), "tshirt");
  EXPECT_EQ(levelNames(fromTshirt), levelNames(levels));
  EXPECT_EQ(fromTshirt.at("levels")[0].at("summary"), "about 6 s to rest, 2 mm from the reference on the tshirt scene");
}

TEST(SpeedAccuracyLevels, RefusesBadReportsNamingTheReportAndTheLevel) {
  {  // a candidate missing from one report
    auto reports = sampleReports();
    auto& runs = reports[1].at("runs");
    runs.erase(
        std::remove_if(runs.begin(), runs.end(), [](const json& r) { return r.value("level", "") == "Accurate"; }),
        runs.end());
    EXPECT_EQ(contains(refusal(reports), {"trade report 'tshirt'", "level 'Accurate'"}), "");
  }
  {  // a report without candidates (only its reference run)
    auto reports = sampleReports();
    reports[1]["runs"] = json::array({reports[1].at("runs")[0]});
    EXPECT_EQ(contains(refusal(reports), {"trade report 'tshirt'", "no candidate"}), "");
  }
  {  // a candidate only one report has
    auto reports = sampleReports();
    json extra = runOf(reports[1], "Fast");
    extra["level"] = "Extra";
    reports[1].at("runs").push_back(extra);
    EXPECT_EQ(contains(refusal(reports), {"trade report 'tshirt'", "level 'Extra'"}), "");
  }
  {  // a run without its wall time
    auto reports = sampleReports();
    runOf(reports[0], "Fast").erase("wall_time_s");
    EXPECT_EQ(contains(refusal(reports), {"trade report 'default'", "level 'Fast'", "wall_time_s"}), "");
  }
  {  // a distance that is not a number (a NaN the bench wrote as null)
    auto reports = sampleReports();
    runOf(reports[1], "Balanced")["mean_distance_mm"] = nullptr;
    EXPECT_EQ(contains(refusal(reports), {"trade report 'tshirt'", "level 'Balanced'", "mean_distance_mm"}), "");
  }
  {  // a candidate measured with other settings in one report (reports from different candidate files)
    auto reports = sampleReports();
    runOf(reports[1], "Fast")["settings"]["solver.cg.tolerance"] = "0.07";
    EXPECT_EQ(contains(refusal(reports), {"trade report 'tshirt'", "level 'Fast'", "other settings"}), "");
  }
  // A reference scene without a report, two reports of one scene, no reports.
  EXPECT_EQ(contains(refusal(sampleReports(), "nowhere"), {"'nowhere'", "default, tshirt"}), "");
  EXPECT_EQ(contains(refusal({sampleReports()[0], sampleReports()[0]}), {"trade report 'default'", "second"}), "");
  EXPECT_THROW(levelsFromReports({}, "default"), InputError);
}

TEST(SpeedAccuracyLevels, ReadsTheLevelsFileBackAndRefusesBadContentNamingTheFileAndLevel) {
  const fs::path file = fs::path(DRAPE_TEST_OUTPUT_DIR) / "speed_accuracy_levels.json";
  const json levels = levelsFromReports(sampleReports(), "default");
  auto write = [&](const json& j) { std::ofstream(file) << j.dump(2) << "\n"; };
  write(levels);
  const std::vector<SpeedAccuracyLevel> read = readSpeedAccuracyLevels(file);
  ASSERT_EQ(read.size(), 3u);
  EXPECT_EQ(read[0].name, "Fast");
  EXPECT_EQ(read[0].settings.at("mesh.target_edge_length"), "0.03");
  EXPECT_DOUBLE_EQ(read[0].wallSeconds, 4.2);
  EXPECT_DOUBLE_EQ(read[0].distanceMm, 1.2);
  EXPECT_TRUE(read[0].atRest);
  EXPECT_EQ(read[0].summary, levels.at("levels")[0].at("summary"));
  EXPECT_FALSE(read[1].atRest);
  EXPECT_EQ(read[2].name, "Accurate");

  auto refusalOf = [&](const json& j) -> std::string {
    write(j);
    try {
      readSpeedAccuracyLevels(file);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "accepted: " << j.dump();
    return "";
  };
  json noSummary = levels;
  noSummary["levels"][1].erase("summary");
  EXPECT_EQ(contains(refusalOf(noSummary), {file.string(), "levels[1] ('Balanced')", "summary"}), "");
  json unknownSetting = levels;
  unknownSetting["levels"][0]["settings"]["solver.newton.h_maxx"] = "0.001";
  EXPECT_EQ(contains(refusalOf(unknownSetting), {file.string(), "levels[0] ('Fast')", "solver.newton.h_maxx"}), "");
  json outOfRange = levels;
  outOfRange["levels"][2]["settings"]["mesh.target_edge_length"] = "-1";
  EXPECT_EQ(contains(refusalOf(outOfRange), {file.string(), "levels[2] ('Accurate')", "mesh.target_edge_length"}), "");
  json numberSetting = levels;
  numberSetting["levels"][0]["settings"]["solver.newton.h_max"] = 0.002;
  EXPECT_EQ(contains(refusalOf(numberSetting), {"levels[0] ('Fast')", "must be a string"}), "");
  EXPECT_EQ(contains(refusalOf(json{{"levels", json::array()}}), {file.string(), "'levels'"}), "");
  fs::remove(file);
  EXPECT_THROW(readSpeedAccuracyLevels(file), InputError);
}

// The committed levels file is what `drape --trade-levels docs/trade/levels/*.json` makes of the committed level
// reports: a changed report, candidate or generator fails here until the file is regenerated (kLevelsCommand). A
// missing file fails too: the GUI's slider reads it.
TEST(SpeedAccuracyLevels, CommittedLevelsFileIsWhatTheCommittedReportsGive) {
  const fs::path source = fs::path(DRAPE_ASSETS_DIR).parent_path();
  const fs::path committed = fs::path(DRAPE_ASSETS_DIR) / "trade" / "speed_accuracy_levels.json";
  ASSERT_TRUE(fs::exists(committed)) << committed.string() << " is missing; generate it with " << kLevelsCommand;
  const json expected = readJson(committed);
  ASSERT_TRUE(expected.contains("reference_scene") && expected.at("reference_scene").is_string())
      << committed.string() << ": no \"reference_scene\"";
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(source / "docs" / "trade" / "levels", ec))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty()) << "no trade reports in " << (source / "docs" / "trade" / "levels").string();
  std::vector<json> reports;
  for (const fs::path& f : files) reports.push_back(readJson(f));
  json generated;
  try {
    generated = levelsFromReports(reports, expected.at("reference_scene").get<std::string>());
  } catch (const InputError& e) {
    FAIL() << e.what();
  }
  EXPECT_EQ(generated, expected) << committed.string() << " is stale; regenerate it with " << kLevelsCommand;
  // The GUI reads it.
  EXPECT_NO_THROW(readSpeedAccuracyLevels(committed));
}

}  // namespace
}  // namespace drape::trade
