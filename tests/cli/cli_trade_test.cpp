// drape --bench (the speed/accuracy trade), --trade-plot and --trade-levels through the executable: the report's rows
// against the reference, in the plot's order, with a front that the test recomputes; the kept reference; the plot
// image; and bad sweeps and reports refused with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_solver_support.h"
#include "drape/render/png_io.h"
#include "run_process.h"

namespace drape::test {
namespace {

// The hanging cloth at 20 cm: a coarse scene whose runs take a fraction of a second.
const std::string kCoarse = " --set mesh.target_edge_length=0.2 --max-sim-time 0.01";

std::string scene() {
  return asset("scenes/hanging_cloth.json");
}

int lineCount(const std::string& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

TEST(CliTrade, SweepReportsEveryRunAgainstTheReferenceInThePlotsOrder) {
  const auto report = kScratch / "trade.json", plot = kScratch / "trade.png";
  std::filesystem::remove(plot);
  auto r = drape("--bench " + scene() + kCoarse +
                 " --sweep solver.cg.tolerance=1e-1,1e-3 --sweep mesh.target_edge_length=0.3 -o " +
                 quote(report.string()) + " --plot " + quote(plot.string()));
#ifdef DRAPE_TEST_WITH_GUI
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
#else
  ASSERT_EQ(r.exitCode, 1) << r.err << r.out;  // the plot needs Qt; the report is written first
#endif
  EXPECT_NE(r.out.find("[5/5]"), std::string::npos) << r.out;  // a progress line per run: reference + 4
  const auto j = nlohmann::json::parse(readWhole(report));
  const auto& runs = j.at("runs");
  ASSERT_EQ(runs.size(), 5u);  // reference, default, two tolerances, one mesh
  // The reference resolves the runs' finest mesh, the scene's 20 cm.
  EXPECT_EQ(j.at("reference").at("settings").count("mesh.target_edge_length"), 0u) << j.at("reference");
  std::vector<std::pair<double, double>> points;
  for (size_t i = 0; i < runs.size(); ++i) {
    const auto& run = runs[i];
    const std::string name = run.at("run");
    if (i > 0) EXPECT_LE(runs[i - 1].at("wall_time_s").get<double>(), run.at("wall_time_s").get<double>()) << name;
    const double mean = run.at("mean_distance_mm"), p95 = run.at("p95_distance_mm"), max = run.at("max_distance_mm");
    EXPECT_LE(mean, max + 1e-12) << name;
    EXPECT_LE(p95, max + 1e-12) << name;
    if (name == "reference") {
      EXPECT_EQ(mean, 0.0);
      EXPECT_EQ(max, 0.0);
      EXPECT_EQ(run.at("stage"), "drape");
    } else {
      EXPECT_EQ(run.at("stage"), "drape") << name;
    }
    // Every reference vertex to the run's surface; vertex to vertex too where the mesh is the reference's, never
    // less (a run's vertex is a point of its surface).
    if (name == "mesh.target_edge_length=0.3") {
      EXPECT_TRUE(run.at("vertex_mean_distance_mm").is_null()) << name;
    } else {
      EXPECT_GE(run.at("vertex_mean_distance_mm").get<double>(), mean - 1e-9) << name;
    }
    const auto terms = run.at("terms").get<std::vector<std::string>>();
    EXPECT_NE(std::find(terms.begin(), terms.end(), "membrane"), terms.end()) << name;
    EXPECT_GT(run.at("steps").get<int>(), 0) << name;
    EXPECT_NEAR(run.at("sim_time_s").get<double>(), 0.01, 2e-3) << name;
    points.emplace_back(run.at("wall_time_s").get<double>(), mean);
  }
  // The front, recomputed: a run is on it when no other is as fast and as close with one of them strictly.
  for (size_t i = 0; i < runs.size(); ++i) {
    bool dominated = false;
    for (size_t k = 0; k < runs.size(); ++k)
      dominated |= points[k].first <= points[i].first && points[k].second <= points[i].second &&
                   (points[k].first < points[i].first || points[k].second < points[i].second);
    EXPECT_EQ(runs[i].at("pareto").get<bool>(), !dominated) << runs[i].at("run");
  }
#ifdef DRAPE_TEST_WITH_GUI
  const render::Image image = render::readPng(plot);
  EXPECT_EQ(image.width, 1200);
  EXPECT_EQ(image.height, 800);
  int drawn = 0;
  for (size_t p = 0; p + 3 < image.pixels.size(); p += 4)
    drawn += image.pixels[p] < 200 || image.pixels[p + 1] < 200 || image.pixels[p + 2] < 200;
  EXPECT_GT(drawn, 2000);  // axes, points, labels and the front; a blank white image has none
#endif
}

TEST(CliTrade, PreviewAndPipelineAreMeasuredAgainstTheDrapeReference) {
  for (const std::string stage : {"preview", "full"}) {
    const auto report = kScratch / ("trade_" + stage + ".json");
    auto r = drape("--bench " + scene() + kCoarse + " --solver " + stage +
                   " --sweep solver.preview.iterations=2 -o " + quote(report.string()));
    ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
    const auto j = nlohmann::json::parse(readWhole(report));
    EXPECT_EQ(j.at("stage"), stage);
    EXPECT_EQ(j.at("reference").at("stage"), "drape");
    ASSERT_EQ(j.at("runs").size(), 3u);
    nlohmann::json referenceTerms;
    for (const auto& run : j.at("runs"))
      if (run.at("run") == "reference") referenceTerms = run.at("terms");
    ASSERT_FALSE(referenceTerms.empty());
    for (const auto& run : j.at("runs")) {
      if (run.at("run") == "reference") continue;
      EXPECT_EQ(run.at("stage"), stage);
      EXPECT_EQ(run.at("terms"), referenceTerms) << run;  // the preview solves the drape's own terms
    }
  }
}

TEST(CliTrade, AKeptReferenceIsReusedAndRefusedForAnotherScene) {
  const auto reference = kScratch / "trade_reference.json";
  std::filesystem::remove(reference);
  const std::string sweep = " --sweep solver.cg.tolerance=1e-1 --reference " + quote(reference.string());
  auto first = drape("--bench " + scene() + kCoarse + sweep);
  ASSERT_EQ(first.exitCode, 0) << first.err << first.out;
  ASSERT_TRUE(std::filesystem::exists(reference));
  EXPECT_NE(first.out.find("[3/3]"), std::string::npos) << first.out;
  // Again, each setting twice in interleaved rounds: the reference is not run again, and a run's wall time is its
  // fastest round's.
  const auto report = kScratch / "trade_rounds.json";
  auto again = drape("--bench " + scene() + kCoarse + sweep + " --rounds 2 -o " + quote(report.string()));
  ASSERT_EQ(again.exitCode, 0) << again.err << again.out;
  EXPECT_NE(again.out.find("reference: "), std::string::npos) << again.out;
  EXPECT_NE(again.out.find("[4/4]"), std::string::npos) << again.out;
  const auto j = nlohmann::json::parse(readWhole(report));
  EXPECT_EQ(j.at("rounds"), 2);
  for (const auto& run : j.at("runs")) {
    const auto walls = run.at("wall_times_s").get<std::vector<double>>();
    ASSERT_EQ(walls.size(), run.at("run") == "reference" ? 1u : 2u) << run.at("run");
    EXPECT_EQ(run.at("wall_time_s").get<double>(), *std::min_element(walls.begin(), walls.end()));
  }
  auto other = drape("--bench " + scene() + " --set mesh.target_edge_length=0.25 --max-sim-time 0.01" + sweep);
  EXPECT_EQ(other.exitCode, 1) << other.out;
  EXPECT_EQ(lineCount(other.err), 1) << other.err;
  EXPECT_NE(other.err.find("trade_reference.json: the reference was made for another scene"), std::string::npos)
      << other.err;
}

TEST(CliTrade, BadSweepsAreRefusedWithOneLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--sweep solver.newton.hmax=1e-3", "solver.newton.hmax"},
      {"--sweep solver.newton.h_max=1", "solver.newton.h_max"},
      {"--sweep solver.newton.h_max=", "empty value"},
      {"--sweep solver.newton.h_max=1e-3,", "empty value"},
      {"--sweep solver.stage=preview", "--solver"},
      {"--sweep h_max", "is not KEY=V1,V2"},
      {"--solver none", "simulates nothing"},
      {"--plot trade.svg", ".png"},
      {"--rounds 0", "--rounds"},
  };
  for (const auto& [args, expected] : cases) {
    auto r = drape("--bench " + scene() + kCoarse + " " + args);
    EXPECT_EQ(r.exitCode, 1) << args;
    EXPECT_EQ(lineCount(r.err), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(r.out.find("reference"), std::string::npos) << args << ": nothing runs before the sweep is checked";
  }
}

TEST(CliTrade, BadReportsAreRefusedWithOneLineNamingTheFile) {
  const auto notJson = kScratch / "not_a_report.json", noRuns = kScratch / "no_runs.json";
  std::filesystem::create_directories(kScratch);
  std::ofstream(notJson) << "{ this is not json";
  std::ofstream(noRuns) << R"({"name": "x", "runs": [{"run": "a"}]})";
  for (const std::string mode : {"--trade-plot", "--trade-levels"}) {
    for (const auto& file : {notJson, noRuns}) {
      auto r = drape(mode + " " + quote(file.string()) + " -o " + quote((kScratch / "out.png").string()));
      EXPECT_EQ(r.exitCode, 1) << mode;
      EXPECT_EQ(lineCount(r.err), 1) << r.err;
      EXPECT_NE(r.err.find(file.filename().string()), std::string::npos) << r.err;
    }
    auto none = drape(mode + " -o " + quote((kScratch / "out.png").string()));
    EXPECT_EQ(none.exitCode, 1);
    EXPECT_NE(none.err.find("no trade report given"), std::string::npos) << none.err;
  }
}

TEST(CliTrade, FailsWhenTheReferenceDoesNotFinishItsDrape) {
  // Three steps of the reference's 0.25 ms cannot reach 0.01 s: the reference stops at the step limit, and the
  // distances to it would measure nothing.
  const auto report = kScratch / "bench_unfinished.json";
  auto r = drape("--bench " + scene() + kCoarse + " --set solver.max_steps=3 --sweep solver.cg.tolerance=1e-1 -o " +
                 quote(report.string()));
  EXPECT_EQ(r.exitCode, 1) << r.err << r.out;
  EXPECT_NE(r.out.find("reference drape ended MaxSteps"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(readWhole(report));
  EXPECT_EQ(j.at("reference").at("status"), "MaxSteps");
}

}  // namespace
}  // namespace drape::test
