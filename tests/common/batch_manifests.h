#pragma once
// What the tests of drape --batch share: running the executable in a scratch folder, writing manifests there, and the
// small tablecloth batches they run.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_process.h"
#include "shared_data.h"

namespace drape::test {

namespace fs = std::filesystem;

inline fs::path batchScratch() { return testOutputDir() / "cli_batch"; }

inline ProcessResult drape(const std::string& args) {
  return runProcess(quote(DRAPE_EXECUTABLE) + " " + args + " </dev/null", batchScratch());
}

// Writes a manifest into the scratch folder and returns its path.
inline fs::path writeManifest(const std::string& name, const nlohmann::json& manifest) {
  fs::create_directories(batchScratch());
  const fs::path file = batchScratch() / name;
  std::ofstream(file) << manifest.dump(2);
  return file;
}

// An asset as the manifests write it: relative to the scratch folder, where they are.
inline std::string relativeAsset(const std::string& relative) {
  return fs::relative(assetsDir() / relative, batchScratch()).string();
}

inline std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

// The progress lines ("[done/failed/total] ...") of a batch's output.
inline std::vector<std::string> progressLines(const std::string& out) {
  std::vector<std::string> lines;
  for (const auto& line : linesOf(out))
    if (line.rfind("[", 0) == 0) lines.push_back(line);
  return lines;
}

inline bool mentions(const std::vector<std::string>& lines, const std::string& text) {
  for (const auto& line : lines)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

// The tablecloth with the given set variations, coarse and short (well under a second per job).
inline nlohmann::json tableclothBatch(const nlohmann::json& sets) {
  return {{"max_sim_time", 0.1},
          {"set", {"mesh.target_edge_length=0.1", "quality.require_rest=false"}},
          {"grid", {{"scenes", {relativeAsset("scenes/tablecloth.json")}}, {"sets", sets}}}};
}

// Four tablecloth jobs: set0 and set1 succeed, set2 is refused at load (exit 1), set3's drape fails its quality verdict
// (no strain passes: exit 4), which still finishes the job.
inline nlohmann::json fourJobBatch() {
  using nlohmann::json;
  return tableclothBatch({json::array({"fabric.density=0.1"}), json::array({"fabric.density=0.2"}),
                          json::array({"fabric.density=-1"}),
                          json::array({"fabric.density=0.3", "quality.max_strain=0"})});
}

// summary.json of OUTDIR without the rows' wall times, which differ from run to run.
inline nlohmann::json summaryWithoutWallTimes(const fs::path& outDir) {
  nlohmann::json rows = nlohmann::json::parse(readWhole(outDir / "summary.json"));
  for (auto& row : rows) row.erase("wall_time_s");
  return rows;
}

}  // namespace drape::test
