// drape --batch through the executable: a manifest's grid and jobs expand to the expected sorted ids, bad manifests are
// refused with one line before any job runs, and a small local batch records its one bad job, writes the summary and
// contact sheet, and on a second run redoes only the jobs without done.json; its shards (--shard I/N) gathered
// (--gather) give the same summary. A batch killed and run again is a slow test (tests/slow/cli_batch_kill_test.cpp),
// and so is the batch through a real Slurm (tests/slow/cli_batch_slurm_test.cpp).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "batch_manifests.h"

namespace drape::test {
namespace {

using nlohmann::json;

TEST(CliBatch, GridAndJobsExpandToStableSortedIds) {
  const json manifest = {
      {"grid",
       {{"scenes", {relativeAsset("scenes/tablecloth.json"), relativeAsset("patterns/hanging_cloth.json")}},
        {"fabrics", {"denim", "silk_charmeuse"}},
        {"sets", {json::array({"fabric.density=0.1"}), json::array()}}}},
      {"jobs",
       {{{"scene", relativeAsset("scenes/tablecloth.json")}, {"id", "custom"}},
        {{"scene", relativeAsset("scenes/tablecloth.json")},
         {"avatar", relativeAsset("avatars/female.yaml")},
         {"set", {"mesh.target_edge_length=0.1"}}}}}};
  const auto r = drape("--batch " + quote(writeManifest("grid.json", manifest).string()) + " --list");
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  std::vector<std::string> ids;
  for (const auto& line : linesOf(r.out)) ids.push_back(line.substr(0, line.find('\t')));
  const std::vector<std::string> expected = {"custom",
                                             "hanging_cloth__denim__set0",
                                             "hanging_cloth__denim__set1",
                                             "hanging_cloth__silk_charmeuse__set0",
                                             "hanging_cloth__silk_charmeuse__set1",
                                             "tablecloth__denim__set0",
                                             "tablecloth__denim__set1",
                                             "tablecloth__female__mesh.target_edge_length_0.1",
                                             "tablecloth__silk_charmeuse__set0",
                                             "tablecloth__silk_charmeuse__set1"};
  EXPECT_EQ(ids, expected) << r.out;
  // The line of a job names its inputs as the manifest wrote them.
  EXPECT_NE(r.out.find("tablecloth__denim__set0\t" + relativeAsset("scenes/tablecloth.json") +
                       "\t-\t-\tdenim\tfabric.density=0.1\n"),
            std::string::npos)
      << r.out;
}

TEST(CliBatch, GradedSizesKeepTheManifestsOrderWithTheirScales) {
  const json manifest = {
      {"grid",
       {{"scenes", {relativeAsset("scenes/tshirt.json")}},
        {"sizes",
         {{"measurements", relativeAsset("avatars/female.yaml")},
          {"scales", {{{"name", "S"}, {"scale", 0.95}}, {{"name", "M"}, {"scale", 1}}, {{"name", "L"}, {"scale", 1.05}}}}}},
        {"fabrics", {"denim"}}}}};
  const auto r = drape("--batch " + quote(writeManifest("sizes.json", manifest).string()) + " --list");
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const std::string scene = relativeAsset("scenes/tshirt.json"), body = relativeAsset("avatars/female.yaml");
  EXPECT_EQ(r.out, "tshirt__0_S__denim\t" + scene + "\t" + body + "\tS x0.95\tdenim\t-\n" +  //
                       "tshirt__1_M__denim\t" + scene + "\t" + body + "\tM x1.0\tdenim\t-\n" +  //
                       "tshirt__2_L__denim\t" + scene + "\t" + body + "\tL x1.05\tdenim\t-\n");
}

TEST(CliBatch, BadManifestsAreRefusedWithOneLineBeforeAnyJobRuns) {
  const std::string cloth = relativeAsset("scenes/tablecloth.json");
  const json grid = {{"scenes", {cloth}}};
  const std::string female = relativeAsset("avatars/female.yaml");
  const json sizes = {{{"name", "M"}, {"scale", 1.0}}};
  struct Case {
    std::string name;
    json manifest;
    std::string element;  // what follows "MANIFEST: "
  };
  const std::vector<Case> cases = {
      {"unknown_key", {{"grid", grid}, {"solvr", "drape"}}, "solvr: unknown key"},
      {"unknown_grid_key", {{"grid", {{"scenes", {cloth}}, {"fabric", {"denim"}}}}}, "grid.fabric: unknown key"},
      {"missing_file", {{"grid", {{"scenes", {"no_such_scene.json"}}}}}, "grid.scenes[0]: file not found"},
      {"empty_axis", {{"grid", {{"scenes", json::array()}}}}, "grid.scenes: empty list"},
      {"empty_grid", {{"grid", json::object()}}, "grid.scenes: missing"},
      {"no_jobs", {{"solver", "drape"}}, "jobs: the manifest has no jobs"},
      {"duplicate_ids",
       {{"jobs", {{{"scene", cloth}, {"id", "same"}}, {{"scene", cloth}, {"id", "same"}}}}},
       "jobs[1]: job id 'same' is also the id of jobs[0]"},
      {"duplicate_derived_ids", {{"grid", grid}, {"jobs", {{{"scene", cloth}}}}}, "jobs[0]: job id 'tablecloth'"},
      {"wrong_type", {{"grid", grid}, {"max_sim_time", "1"}}, "max_sim_time: must be a positive number"},
      {"unknown_fabric", {{"grid", {{"scenes", {cloth}}, {"fabrics", {"tweed"}}}}}, "grid.fabrics[0]: unknown fabric"},
      {"unknown_setting", {{"grid", grid}, {"set", {"mesh.edge=0.1"}}}, "set[0]: unknown setting 'mesh.edge'"},
      {"bad_output", {{"grid", grid}, {"outputs", {"obj", "fbx"}}}, "outputs[1]: 'fbx' is not one of"},
      {"sizes_and_avatars",
       {{"grid", {{"scenes", {cloth}}, {"avatars", {female}}, {"sizes", {{"measurements", female}, {"scales", sizes}}}}}},
       "grid.sizes: not with grid.avatars"},
      {"size_of_a_mesh",
       {{"grid", {{"scenes", {cloth}}, {"sizes", {{"measurements", relativeAsset("avatars/female.obj")}, {"scales", sizes}}}}}},
       "grid.sizes.measurements: must be a body-measurement file"},
      {"size_scale",
       {{"grid",
         {{"scenes", {cloth}}, {"sizes", {{"measurements", female}, {"scales", {{{"name", "XXL"}, {"scale", 3}}}}}}}}},
       "grid.sizes.scales[0].scale: must be a number from 0.5 to 2, got 3"},
      {"size_name",
       {{"grid", {{"scenes", {cloth}}, {"sizes", {{"measurements", female}, {"scales", {{{"scale", 1}}}}}}}}},
       "grid.sizes.scales[0].name: missing"}};
  for (const Case& c : cases) {
    const fs::path file = writeManifest("bad_" + c.name + ".json", c.manifest);
    const fs::path outDir = batchScratch() / ("out_bad_" + c.name);
    fs::remove_all(outDir);
    const auto r = drape("--batch " + quote(file.string()) + " -o " + quote(outDir.string()));
    EXPECT_EQ(r.exitCode, 1) << c.name << ": " << r.err << r.out;
    EXPECT_EQ(linesOf(r.err).size(), 1u) << c.name << ": " << r.err;
    EXPECT_EQ(r.err.rfind("drape: " + file.string() + ": " + c.element, 0), 0u) << c.name << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << c.name << ": " << r.out;
    EXPECT_FALSE(fs::exists(outDir)) << c.name;
  }
}

TEST(CliBatch, OnlyTheOutputsAskedForAreKept) {
  json manifest = tableclothBatch(json::array({json::array()}));  // one set: no extra settings
  manifest["solver"] = "none";
  manifest["outputs"] = {"glb", "stats"};
  const fs::path outDir = batchScratch() / "out_glb";
  fs::remove_all(outDir);
  const auto r =
      drape("--batch " + quote(writeManifest("glb.json", manifest).string()) + " -o " + quote(outDir.string()));
  ASSERT_EQ(r.exitCode, 0) << r.err << r.out;
  const fs::path job = outDir / "tablecloth__set0";
  EXPECT_TRUE(fs::exists(job / "garment.glb"));
  EXPECT_TRUE(fs::exists(job / "stats.json"));
  EXPECT_FALSE(fs::exists(job / "garment.obj"));
  EXPECT_FALSE(fs::exists(job / "garment.png"));
  const json row = json::parse(readWhole(outDir / "summary.json")).at(0);
  EXPECT_EQ(row.at("glb"), "tablecloth__set0/garment.glb");
  EXPECT_EQ(row.at("obj"), "");
  EXPECT_EQ(row.at("status"), "Placed");
}

TEST(CliBatch, LocalBatchRecordsTheBadJobAndARerunRedoesOnlyUnfinishedJobs) {
  const fs::path file = writeManifest("local.json", fourJobBatch()), outDir = batchScratch() / "out_local";
  fs::remove_all(outDir);
  const std::string command = "--batch " + quote(file.string()) + " -o " + quote(outDir.string()) + " --jobs 2";
  auto r = drape(command);
  ASSERT_EQ(r.exitCode, 5) << r.err << r.out;  // some jobs failed
  auto progress = progressLines(r.out);
  ASSERT_EQ(progress.size(), 4u) << r.out;
  EXPECT_EQ(progress.back().rfind("[2/2/4] ", 0), 0u) << r.out;
  EXPECT_TRUE(mentions(progress, "last: tablecloth__set2 Failed (exit 1)")) << r.out;
  EXPECT_TRUE(mentions(progress, "last: tablecloth__set3 MaxSimTime (exit 4: quality failed)")) << r.out;

  const json rows = json::parse(readWhole(outDir / "summary.json"));
  ASSERT_EQ(rows.size(), 4u);
  for (const json& row : rows) {
    const std::string id = row.at("id");
    const fs::path job = outDir / id;
    if (id == "tablecloth__set2") {
      EXPECT_EQ(row.at("status"), "Failed");
      EXPECT_EQ(row.at("exit_status"), 1);
      EXPECT_NE(row.at("error").get<std::string>().find("fabric.density"), std::string::npos) << row;
      EXPECT_EQ(row.at("set"), "fabric.density=-1");
      EXPECT_TRUE(fs::exists(job / "failed.json"));
      EXPECT_FALSE(fs::exists(job / "done.json"));
    } else {
      const bool strained = id == "tablecloth__set3";
      EXPECT_EQ(row.at("status"), "MaxSimTime") << row;
      EXPECT_EQ(row.at("exit_status"), strained ? 4 : 0) << row;
      EXPECT_EQ(row.at("quality_passed"), !strained) << row;
      EXPECT_EQ(row.at("at_rest"), false) << row;
      EXPECT_GT(row.at("steps").get<int>(), 0) << row;
      EXPECT_EQ(row.at("inside_vertices"), 0) << row;
      EXPECT_TRUE(fs::exists(outDir / row.at("obj").get<std::string>())) << row;
      EXPECT_TRUE(fs::exists(outDir / row.at("png").get<std::string>())) << row;
      EXPECT_EQ(json::parse(readWhole(job / "done.json")), row);
    }
  }
  const auto csv = linesOf(readWhole(outDir / "summary.csv"));
  ASSERT_EQ(csv.size(), 5u);
  EXPECT_EQ(csv[0].rfind("id,scene,avatar,size,fabric,set,status,exit_status,error,", 0), 0u) << csv[0];
  EXPECT_EQ(csv[3].rfind("tablecloth__set2,", 0), 0u) << csv[3];
#ifdef DRAPE_TEST_WITH_GUI
  // A PNG whose width (IHDR, big-endian at byte 16) holds the four 256-pixel thumbnails side by side.
  const std::string sheet = readWhole(outDir / "contact_sheet.png");
  ASSERT_GT(sheet.size(), 24u);
  EXPECT_EQ(sheet.substr(1, 3), "PNG");
  const auto byte = [&](int i) { return static_cast<unsigned>(static_cast<unsigned char>(sheet[i])); };
  EXPECT_GE(byte(16) << 24 | byte(17) << 16 | byte(18) << 8 | byte(19), 4u * 256u);
#endif

  // Again, with one good job's done.json gone: that job and the failed one run, the other two (the one whose quality
  // verdict failed among them) are left alone.
  const auto before0 = fs::last_write_time(outDir / "tablecloth__set0" / "done.json");
  const auto before3 = fs::last_write_time(outDir / "tablecloth__set3" / "done.json");
  fs::remove(outDir / "tablecloth__set1" / "done.json");
  r = drape(command);
  ASSERT_EQ(r.exitCode, 5) << r.err << r.out;
  EXPECT_NE(r.out.find("4 jobs, 2 finished before; running 2"), std::string::npos) << r.out;
  progress = progressLines(r.out);
  ASSERT_EQ(progress.size(), 2u) << r.out;
  EXPECT_TRUE(mentions(progress, "last: tablecloth__set1 MaxSimTime")) << r.out;
  EXPECT_TRUE(mentions(progress, "last: tablecloth__set2 Failed")) << r.out;
  EXPECT_EQ(progress.back().rfind("[2/2/4] ", 0), 0u) << r.out;
  EXPECT_TRUE(fs::exists(outDir / "tablecloth__set1" / "done.json"));
  EXPECT_EQ(fs::last_write_time(outDir / "tablecloth__set0" / "done.json"), before0);
  EXPECT_EQ(fs::last_write_time(outDir / "tablecloth__set3" / "done.json"), before3);
  EXPECT_EQ(json::parse(readWhole(outDir / "summary.json")).size(), 4u);
}

TEST(CliBatch, ShardsRunTheirJobsAloneAndGatherWritesTheSummaryOfTheWholeBatch) {
  const fs::path file = writeManifest("shards.json", fourJobBatch());
  const fs::path local = batchScratch() / "out_shards_local", sharded = batchScratch() / "out_shards";
  fs::remove_all(local);
  fs::remove_all(sharded);
  ASSERT_EQ(drape("--batch " + quote(file.string()) + " -o " + quote(local.string())).exitCode, 5);

  // Shard 1/2 holds the jobs of index 1 and 3 (set1 succeeds, set3 fails its quality verdict): it runs them alone and
  // writes no summary.
  const std::string command = "--batch " + quote(file.string()) + " -o " + quote(sharded.string());
  auto r = drape(command + " --shard 1/2");
  ASSERT_EQ(r.exitCode, 5) << r.err << r.out;
  EXPECT_NE(r.out.find("shard 1/2: 2 jobs, 0 finished before; running 2"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(sharded / "tablecloth__set1" / "done.json"));
  EXPECT_TRUE(fs::exists(sharded / "tablecloth__set3" / "done.json"));
  EXPECT_FALSE(fs::exists(sharded / "tablecloth__set0"));
  EXPECT_FALSE(fs::exists(sharded / "tablecloth__set2"));
  EXPECT_FALSE(fs::exists(sharded / "summary.json"));

  // Gathered now, the jobs of shard 0 are failed rows that say they never ran.
  r = drape(command + " --gather");
  ASSERT_EQ(r.exitCode, 5) << r.err << r.out;
  json rows = json::parse(readWhole(sharded / "summary.json"));
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].at("status"), "Failed");
  EXPECT_NE(rows[0].at("error").get<std::string>().find("no record of this job"), std::string::npos) << rows[0];

  // After shard 0/2 the gathered summary is the one-machine batch's, row for row, but for the wall times.
  r = drape(command + " --shard 0/2");
  ASSERT_EQ(r.exitCode, 5) << r.err << r.out;
  EXPECT_NE(r.out.find("shard 0/2: 2 jobs, 0 finished before; running 2"), std::string::npos) << r.out;
  r = drape(command + " --gather");
  ASSERT_EQ(r.exitCode, 5) << r.err << r.out;
  EXPECT_TRUE(progressLines(r.out).empty()) << r.out;  // gathering runs no job
  EXPECT_EQ(summaryWithoutWallTimes(sharded), summaryWithoutWallTimes(local));
  EXPECT_TRUE(fs::exists(sharded / "contact_sheet.png"));
}

TEST(CliBatch, BadShardAndSlurmOptionsAreRefusedWithOneLine) {
  const std::string batch = "--batch " + quote(writeManifest("options.json", fourJobBatch()).string()) + " -o " +
                            quote((batchScratch() / "out_options").string());
  const std::vector<std::pair<std::string, std::string>> cases = {
      {batch + " --shard 2/2", "--shard: '2/2' is not I/N with 0 <= I < N <= 1000"},
      {batch + " --shard 1", "--shard: '1' is not I/N"},
      {batch + " --shard 0/0", "--shard: '0/0' is not I/N"},
      {batch + " --shard 0/2 --gather", "--list, --gather, --slurm, --shard: one at a time"},
      {batch + " --partition debug", "--partition, --time, --cpus-per-task, --tasks: only with --slurm"},
      {batch + " --slurm --tasks 0", "--tasks: '0' is not a number of array tasks from 1 to 1000"},
      {batch + " --slurm --partition 'a b'", "--partition: 'a b' is not a Slurm name or time"},
      {"--simulate x.json -o x.obj --gather", "--jobs, --list, --shard, --gather, --slurm: only with --batch"},
      {"--info x.json --threads 0", "--threads: '0' is not a number of threads from 1 to 1024"}};
  for (const auto& [args, message] : cases) {
    const auto r = drape(args);
    EXPECT_EQ(r.exitCode, 1) << args << ": " << r.err << r.out;
    EXPECT_EQ(linesOf(r.err).size(), 1u) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("drape: " + message, 0), 0u) << args << ": " << r.err;
  }
  // Without sbatch the submission says where to run it and submits nothing.
  const auto r = runProcess("env PATH=/nonexistent " + quote(DRAPE_EXECUTABLE) + " " + batch + " --slurm </dev/null",
                            batchScratch());
  EXPECT_EQ(r.exitCode, 1) << r.err << r.out;
  EXPECT_EQ(r.err.rfind("drape: --slurm: sbatch is not on PATH", 0), 0u) << r.err;
  EXPECT_FALSE(fs::exists(batchScratch() / "out_options" / ".slurm" / "submitted.txt"));
}

}  // namespace
}  // namespace drape::test
