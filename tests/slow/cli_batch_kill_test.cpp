// drape --batch through the executable, killed: the batch killed (SIGKILL to it and its running job) once its first
// job has finished keeps the finished drapes, and the same command again runs only the others. The batch's other
// tests are in tests/cli/cli_batch_test.cpp.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "batch_manifests.h"

namespace drape::test {
namespace {

using nlohmann::json;

// The batch killed (SIGKILL to it and its running job) once its first job has finished: the finished drapes stay, and
// the same command again runs only the others.
TEST(CliBatch, AKilledBatchKeepsItsFinishedDrapesAndTheRerunRunsOnlyTheRest) {
  json manifest = tableclothBatch({json::array({"fabric.density=0.1"}), json::array({"fabric.density=0.2"}),
                                   json::array({"fabric.density=0.3"}), json::array({"fabric.density=0.4"})});
  // About a second a job: time to kill the batch while its second job runs.
  manifest["max_sim_time"] = 1.0;
  // Self-contact on: the coarse tablecloth folds onto itself, and the verdict passes no crossing.
  manifest["set"] = {"mesh.target_edge_length=0.05", "quality.require_rest=false", "contact.self_collision=true"};
  const fs::path file = writeManifest("killed.json", manifest), outDir = batchScratch() / "out_killed";
  fs::remove_all(outDir);
  const std::string command = "--batch " + quote(file.string()) + " -o " + quote(outDir.string()) + " --jobs 1";
  // setsid: the batch leads its own process group, which the kill takes down with its child.
  const ProcessResult started =
      runProcess("setsid " + quote(DRAPE_EXECUTABLE) + " " + command + " </dev/null >/dev/null 2>&1 & echo $!",
                 batchScratch());
  const pid_t pid = std::stoi(linesOf(started.out).at(0));
  auto finished = [&] {
    std::vector<std::string> ids;
    for (int i = 0; i < 4; ++i)
      if (fs::exists(outDir / ("tablecloth__set" + std::to_string(i)) / "done.json"))
        ids.push_back("tablecloth__set" + std::to_string(i));
    return ids;
  };
  // Running, and not a zombie that nobody reaps yet (its parent shell has exited).
  auto alive = [&] {
    if (::kill(pid, 0) != 0) return false;
    const std::string stat = readWhole("/proc/" + std::to_string(pid) + "/stat");
    const auto paren = stat.rfind(')');
    return paren != std::string::npos && paren + 2 < stat.size() && stat[paren + 2] != 'Z';
  };
  for (int i = 0; i < 6000 && finished().empty() && alive(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ::kill(-pid, SIGKILL);
  for (int i = 0; i < 1000 && alive(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const std::vector<std::string> before = finished();
  ASSERT_GE(before.size(), 1u);
  ASSERT_LT(before.size(), 4u) << "the batch ended before it was killed";
  EXPECT_FALSE(fs::exists(outDir / "summary.json"));
  std::vector<fs::file_time_type> times;
  for (const auto& id : before) times.push_back(fs::last_write_time(outDir / id / "done.json"));

  const ProcessResult r = drape(command);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("4 jobs, " + std::to_string(before.size()) + " finished before; running " +
                       std::to_string(4 - before.size())),
            std::string::npos)
      << r.out;
  EXPECT_EQ(progressLines(r.out).size(), 4 - before.size()) << r.out;
  EXPECT_EQ(finished().size(), 4u);
  for (size_t i = 0; i < before.size(); ++i)
    EXPECT_EQ(fs::last_write_time(outDir / before[i] / "done.json"), times[i]) << before[i];
  EXPECT_EQ(json::parse(readWhole(outDir / "summary.json")).size(), 4u);
}

}  // namespace
}  // namespace drape::test
