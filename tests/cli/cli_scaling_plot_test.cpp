// drape --scaling-plot: bench/scaling.py's report (rounds of one scene at several edge lengths) drawn as a log-log plot
// of time to rest and peak memory against the vertex count, by the trade plot's machinery; bad reports refused with
// one line naming the file and the run.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_solver_support.h"
#include "drape/render/png_io.h"
#include "run_process.h"

namespace drape::test {
namespace {

nlohmann::json run(double edge, int vertices, double wall, double peak) {
  return {{"edge_cm", edge}, {"vertices", vertices}, {"wall_s", wall}, {"peak_mb", peak}, {"steps", 500}};
}

TEST(CliScalingPlot, DrawsTimeAndMemoryAgainstVertices) {
  std::filesystem::create_directories(kScratch);
  const auto report = kScratch / "scaling.json", plot = kScratch / "scaling.png";
  nlohmann::json j = {{"scene", "bench/scenes/tshirt_female.json"},
                      {"rounds",
                       {{run(3, 1200, 2.1, 150), run(2, 2600, 5.0, 180), run(1, 10456, 25.0, 320)},
                        {run(3, 1200, 2.3, 151), run(2, 2600, 4.6, 182), run(1, 10456, 27.0, 318)}}}};
  std::ofstream(report) << j.dump();
  auto r = drape("--scaling-plot " + quote(report.string()) + " -o " + quote(plot.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("3 mesh sizes, 2 rounds"), std::string::npos) << r.out;
#ifdef DRAPE_TEST_WITH_GUI
  const render::Image image = render::readPng(plot);
  EXPECT_EQ(image.width, 1200);
  EXPECT_EQ(image.height, 800);
  // Both series are drawn: pixels of the first palette colour (#1f77b4, time) and of the second (#ff7f0e, memory).
  int blue = 0, orange = 0;
  for (size_t p = 0; p + 3 < image.pixels.size(); p += 4) {
    const int red = image.pixels[p], green = image.pixels[p + 1], b = image.pixels[p + 2];
    blue += std::abs(red - 0x1f) < 12 && std::abs(green - 0x77) < 12 && std::abs(b - 0xb4) < 12;
    orange += std::abs(red - 0xff) < 12 && std::abs(green - 0x7f) < 12 && std::abs(b - 0x0e) < 12;
  }
  EXPECT_GT(blue, 200);
  EXPECT_GT(orange, 200);
#endif
}

TEST(CliScalingPlot, BadReportsAreRefusedWithOneLineNamingTheFileAndTheRun) {
  std::filesystem::create_directories(kScratch);
  const auto notJson = kScratch / "scaling_not_json.json", noRounds = kScratch / "scaling_no_rounds.json",
             badRun = kScratch / "scaling_bad_run.json";
  std::ofstream(notJson) << "{ not json";
  std::ofstream(noRounds) << R"({"scene": "x"})";
  nlohmann::json bad = {{"rounds", {{run(3, 1200, 2.1, 150), run(2, -5, 5.0, 180)}}}};
  std::ofstream(badRun) << bad.dump();
  const auto png = quote((kScratch / "scaling_out.png").string());
  for (const auto& [file, says] : {std::pair{notJson, std::string("not JSON")},
                                   std::pair{noRounds, std::string("no \"rounds\"")},
                                   std::pair{badRun, std::string("round 0 run 1: \"vertices\"")}}) {
    auto r = drape("--scaling-plot " + quote(file.string()) + " -o " + png);
    EXPECT_EQ(r.exitCode, 1) << file;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(file.filename().string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(kScratch / "scaling_out.png"));
}

}  // namespace
}  // namespace drape::test
