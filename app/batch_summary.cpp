#include "batch_summary.h"

#include <cmath>
#include <sstream>

#include "drape/io/atomic_file.h"
#include "quality_output.h"

namespace drape::app {
namespace {

using nlohmann::json;

// The columns of summary.csv, in order; the keys of a row.
const std::vector<std::string> kColumns = {"id",
                                           "scene",
                                           "avatar",
                                           "size",
                                           "fabric",
                                           "set",
                                           "status",
                                           "exit_status",
                                           "error",
                                           "wall_time_s",
                                           "sim_time_s",
                                           "steps",
                                           "max_strain",
                                           "inside_vertices",
                                           "self_intersections",
                                           "at_rest",
                                           "quality_passed",
                                           "obj",
                                           "glb",
                                           "png",
                                           "stats"};

// The value of a quality check in the stats, or null when the stats have no such check.
json checkValue(const json& stats, const char* name) {
  if (!stats.contains("quality") || !stats.at("quality").contains("checks")) return nullptr;
  const json& checks = stats.at("quality").at("checks");
  return checks.contains(name) ? checks.at(name).value("value", json(nullptr)) : json(nullptr);
}

json valueOr(const json& stats, const char* key) {
  return stats.contains(key) ? stats.at(key) : json(nullptr);
}

// A CSV field: quoted when it holds a separator, a quote or a line break (quotes doubled).
std::string csvField(const json& value) {
  std::string text;
  if (value.is_null()) return "";
  if (value.is_string())
    text = value.get<std::string>();
  else if (value.is_boolean())
    text = value.get<bool>() ? "true" : "false";
  else
    text = value.dump();
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

json summaryRow(const BatchJob& job, const BatchJobOutcome& outcome,
                const std::vector<std::pair<std::string, std::string>>& outputs) {
  const json& stats = outcome.stats.is_object() ? outcome.stats : json::object();
  json row = {{"id", job.id},
              {"scene", job.scene.text},
              {"avatar", job.avatar.text},
              {"size", job.size},
              {"fabric", job.fabric},
              {"set", job.setLabel},
              {"status", stats.contains("status") ? stats.at("status") : json("Failed")},
              {"exit_status", outcome.exitStatus},
              {"error", outcome.error},
              {"wall_time_s", outcome.wallTime},
              {"sim_time_s", valueOr(stats, "sim_time_s")},
              {"steps", valueOr(stats, "steps")}};
  // The quality checks hold the final state's numbers; a run without a verdict (solver none) has none.
  row["max_strain"] = checkValue(stats, "max_strain");
  const json inside = checkValue(stats, "inside_fraction");
  row["inside_vertices"] = inside.is_number() && stats.contains("vertices")
                               ? json(std::lround(inside.get<double>() * stats.at("vertices").get<double>()))
                               : json(nullptr);
  const json crossings = checkValue(stats, "self_intersections");
  row["self_intersections"] = crossings.is_number() ? json(std::lround(crossings.get<double>())) : json(nullptr);
  row["at_rest"] = stats.contains("status") ? json(stats.at("status") == "AtRest") : json(nullptr);
  row["quality_passed"] =
      stats.contains("quality") ? stats.at("quality").value("passed", json(nullptr)) : json(nullptr);
  for (const char* key : {"obj", "glb", "png", "stats"}) row[key] = "";
  for (const auto& [key, path] : outputs) row[key] = path;
  return row;
}

std::string statusText(const json& row) {
  std::string text = row.at("status").get<std::string>();
  const int exit = row.at("exit_status").get<int>();
  if (exit == 4)
    text += " (exit 4: quality failed)";
  else if (exit != 0)
    text += " (exit " + std::to_string(exit) + ")";
  return text;
}

bool rowSucceeded(const json& row) {
  return row.at("exit_status").get<int>() == 0;
}

bool rowFinished(const json& row) {
  const int exit = row.at("exit_status").get<int>();
  return exit == 0 || exit == kQualityFailedExit;
}

void writeBatchSummary(const std::vector<json>& rows, const std::filesystem::path& outDir) {
  std::ostringstream csv;
  for (size_t i = 0; i < kColumns.size(); ++i) csv << (i ? "," : "") << kColumns[i];
  csv << "\n";
  for (const json& row : rows) {
    for (size_t i = 0; i < kColumns.size(); ++i)
      csv << (i ? "," : "") << csvField(row.contains(kColumns[i]) ? row.at(kColumns[i]) : json(nullptr));
    csv << "\n";
  }
  writeFileAtomically(outDir / "summary.csv", csv.str());
  writeFileAtomically(outDir / "summary.json", json(rows).dump(2) + "\n");
}

}  // namespace drape::app
