// drape --batch --slurm through a real Slurm: the one-node cluster of scripts/slurm-local.sh, started here when it is
// not up (and stopped again after). Where it cannot start (not root, packages missing) the test is skipped with the
// reason; with DRAPE_REQUIRE_SLURM=1 (CI) that fails it instead.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "batch_manifests.h"

namespace drape::test {
namespace {

using nlohmann::json;

const fs::path kSlurmScript = fs::path(DRAPE_SOURCE_DIR) / "scripts" / "slurm-local.sh";

class CliBatchSlurm : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (runProcess("bash " + quote(kSlurmScript.string()) + " status", batchScratch()).exitCode == 0) {
      ready_ = true;
      return;
    }
    if (::geteuid() != 0) {
      why_ = "scripts/slurm-local.sh start needs root";
      return;
    }
    const ProcessResult r = runProcess("bash " + quote(kSlurmScript.string()) + " start", batchScratch());
    ready_ = startedHere_ = r.exitCode == 0;
    why_ = r.err.empty() ? r.out : r.err;
  }
  static void TearDownTestSuite() {
    if (startedHere_) runProcess("bash " + quote(kSlurmScript.string()) + " stop", batchScratch());
  }
  void SetUp() override {
    if (ready_) return;
    const char* required = std::getenv("DRAPE_REQUIRE_SLURM");
    if (required && std::string(required) == "1") FAIL() << "the local Slurm did not start: " << why_;
    GTEST_SKIP() << "the local Slurm did not start (" << why_ << "); run scripts/slurm-local.sh start as root";
  }

  static inline bool ready_ = false, startedHere_ = false;
  static inline std::string why_;
};

// The number after `text` in the submission's line ("job array 12 (", "then job 13,").
std::string idAfter(const std::string& out, const std::string& text) {
  const auto at = out.find(text);
  if (at == std::string::npos) return "";
  const auto begin = at + text.size();
  return out.substr(begin, out.find_first_not_of("0123456789", begin) - begin);
}

// Waits until squeue lists none of the jobs; false after a bound far beyond what the batch needs (a hung cluster).
bool waitForSlurmJobs(const std::string& ids) {
  for (int i = 0; i < 600; ++i) {
    const ProcessResult r = runProcess("squeue -h -o %i -j " + ids, batchScratch());
    if (r.exitCode == 0 && r.out.empty()) return true;
    if (r.exitCode != 0 && r.err.find("Invalid job id") != std::string::npos) return true;  // already forgotten
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  return false;
}

TEST_F(CliBatchSlurm, AnArrayOfTwoTasksGivesTheSummaryOfTheLocalRunAndResubmitsOnlyUnfinishedShards) {
  const fs::path file = writeManifest("slurm.json", fourJobBatch());
  const fs::path local = batchScratch() / "out_slurm_local", cluster = batchScratch() / "out_slurm";
  fs::remove_all(local);
  fs::remove_all(cluster);
  ASSERT_EQ(drape("--batch " + quote(file.string()) + " -o " + quote(local.string())).exitCode, 5);

  const std::string submit = "--batch " + quote(file.string()) + " -o " + quote(cluster.string()) + " --slurm --tasks 2";
  ProcessResult r = drape(submit);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("4 of 4 jobs submitted to Slurm as job array "), std::string::npos) << r.out;
  const std::string array = idAfter(r.out, "job array "), gather = idAfter(r.out, "then job ");
  ASSERT_FALSE(array.empty()) << r.out;
  ASSERT_FALSE(gather.empty()) << r.out;
  // Submitting again while they are queued or running would start their jobs twice: refused (unless all of them,
  // the gathering job too, ended in between: then there is nothing to submit).
  const ProcessResult again = drape(submit);
  ASSERT_TRUE(waitForSlurmJobs(array + "," + gather)) << "the Slurm jobs did not end";
  if (again.exitCode == 1)
    EXPECT_NE(again.err.find("has Slurm jobs still queued or running"), std::string::npos) << again.err;
  else
    EXPECT_NE(again.out.find("nothing to submit"), std::string::npos) << again.err << again.out;

  const std::string script = readWhole(cluster / ".slurm" / "array.sbatch");
  EXPECT_NE(script.find("#SBATCH --array=0-1\n"), std::string::npos) << script;
  EXPECT_NE(script.find("--shard \"$SLURM_ARRAY_TASK_ID/2\""), std::string::npos) << script;
  EXPECT_TRUE(fs::exists(cluster / ".slurm" / ("task-" + array + "_0.log")));
  EXPECT_TRUE(fs::exists(cluster / ".slurm" / ("task-" + array + "_1.log")));
  // The gathering job wrote the summary and the contact sheet after the array.
  ASSERT_TRUE(fs::exists(cluster / "summary.json")) << readWhole(cluster / ".slurm" / ("gather-" + gather + ".log"));
  EXPECT_EQ(summaryWithoutWallTimes(cluster), summaryWithoutWallTimes(local));
  EXPECT_TRUE(fs::exists(cluster / "contact_sheet.png"));

  // Resubmitted, only shard 0 (set0, whose record is removed here, and the failed set2) has unfinished jobs.
  fs::remove(cluster / "tablecloth__set0" / "done.json");
  r = drape(submit);
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("2 of 4 jobs submitted"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(tasks 0 of shards 0-1)"), std::string::npos) << r.out;
  ASSERT_TRUE(waitForSlurmJobs(idAfter(r.out, "job array ") + "," + idAfter(r.out, "then job ")));
  EXPECT_TRUE(fs::exists(cluster / "tablecloth__set0" / "done.json"));
  EXPECT_EQ(summaryWithoutWallTimes(cluster), summaryWithoutWallTimes(local));
}

}  // namespace
}  // namespace drape::test
