// drape --from STATE.obj: a stage starts at the positions of an OBJ that drape wrote for the same scene; a file of
// another garment is refused with exit status 1 and one line naming it.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "run_process.h"
#include "shared_data.h"

namespace drape::test {
namespace {

const std::filesystem::path kScratch = testOutputDir() / "cli_from";

ProcessResult drape(const std::string& args) {
  std::filesystem::create_directories(kScratch);
  return runProcess(quote(DRAPE_EXECUTABLE) + " " + args + " </dev/null", kScratch);
}

std::string scene(const char* file) {
  return quote((assetsDir() / "scenes" / file).string());
}
std::string path(const char* file) {
  return quote((kScratch / file).string());
}

// The "v" lines of an OBJ as rows of numbers.
std::vector<std::array<double, 3>> vertices(const std::filesystem::path& obj) {
  std::vector<std::array<double, 3>> v;
  std::ifstream in(obj);
  std::string line;
  while (std::getline(in, line)) {
    std::array<double, 3> p{};
    if (line.rfind("v ", 0) == 0 && std::sscanf(line.c_str() + 2, "%lf %lf %lf", &p[0], &p[1], &p[2]) == 3)
      v.push_back(p);
  }
  return v;
}

double largestDifference(const std::vector<std::array<double, 3>>& a, const std::vector<std::array<double, 3>>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(a[i][k] - b[i][k]));
  return d;
}

TEST(CliFrom, StageNoneWritesTheGivenStateAndAPreviewStartsThere) {
  // The previews are cut short, not at rest: the test is about the states they leave, not their quality verdict.
  const std::string tablecloth =
      scene("tablecloth.json") + " --set mesh.target_edge_length=0.08 --set quality.require_rest=false";
  ASSERT_EQ(drape("--simulate " + tablecloth + " --solver preview --max-sim-time 0.2 -o " + path("state.obj")).exitCode,
            0);
  ASSERT_EQ(drape("--simulate " + tablecloth + " --solver none -o " + path("placed.obj")).exitCode, 0);
  const auto r = drape("--simulate " + tablecloth + " --solver none --from " + path("state.obj") + " -o " +
                       path("copy.obj") + " --stats " + path("copy.json"));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const auto state = vertices(kScratch / "state.obj"), copy = vertices(kScratch / "copy.obj"),
             placed = vertices(kScratch / "placed.obj");
  ASSERT_EQ(copy.size(), state.size());
  EXPECT_EQ(largestDifference(copy, state), 0.0);     // 9 significant digits read and written again
  EXPECT_GT(largestDifference(state, placed), 0.01);  // the preview moved it: the copy is not the placed garment
  const auto stats = nlohmann::json::parse(std::ifstream(kScratch / "copy.json"));
  EXPECT_EQ(stats.at("status"), "FromState");
  EXPECT_EQ(stats.at("from"), (kScratch / "state.obj").string());

  // One more preview step from the state moves it by at most what gravity does in a step, not back to the placed
  // garment's hanging position.
  const auto on = drape("--simulate " + tablecloth + " --solver preview --max-sim-time 0.003 --from " +
                        path("state.obj") + " -o " + path("on.obj"));
  ASSERT_EQ(on.exitCode, 0) << on.err;
  EXPECT_LT(largestDifference(vertices(kScratch / "on.obj"), state), 0.005);
}

TEST(CliFrom, AnotherGarmentsStateIsRefused) {
  const std::string tablecloth = scene("tablecloth.json") + " --set mesh.target_edge_length=0.08";
  ASSERT_EQ(drape("--simulate " + tablecloth + " --solver none -o " + path("coarse.obj")).exitCode, 0);
  for (const char* solver : {"none", "preview", "drape", "full"}) {
    const auto r = drape("--simulate " + scene("tablecloth.json") + " --set mesh.target_edge_length=0.06 --solver " +
                         solver + " --from " + path("coarse.obj") + " -o " + path("finer.obj"));
    EXPECT_EQ(r.exitCode, 1) << solver;
    EXPECT_NE(r.err.find("coarse.obj:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("vertices, the scene's garment has"), std::string::npos) << r.err;
  }
  const auto render = drape("--render " + scene("tablecloth.json") + " --simulate none --from " + path("missing.obj") +
                            " -o " + path("x.png"));
  EXPECT_EQ(render.exitCode, 1);
  EXPECT_NE(render.err.find("missing.obj: cannot open"), std::string::npos) << render.err;
  const auto info = drape("--info " + scene("tablecloth.json") + " --from " + path("coarse.obj"));
  EXPECT_EQ(info.exitCode, 1);
  EXPECT_NE(info.err.find("--from: only with --simulate or --render"), std::string::npos) << info.err;
}

}  // namespace
}  // namespace drape::test
