// drape --scaling-plot SCALING.json -o SCALING.png: how the drape's cost grows with the mesh (bench/scaling.py's
// report: rounds of runs of one scene at several edge lengths), as a log-log plot drawn by the trade plot's
// machinery: the fastest time to rest and the largest peak memory over the rounds against the vertex count.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>

#include "commands.h"
#include "drape/core/input_error.h"
#ifdef DRAPE_WITH_GUI
#include "drape/qt/trade_plot.h"
#endif

namespace drape::app {
namespace {

struct ScalingRun {
  double edgeCm = 0.0;
  double vertices = 0.0;
  double wallSeconds = 0.0;
  double peakMb = 0.0;
};

double positive(const nlohmann::json& run, const char* key, const std::string& where) {
  if (!run.contains(key) || !run[key].is_number() || !(run[key].get<double>() > 0.0))
    throw InputError(where + ": \"" + key + "\" is missing or not a positive number");
  return run[key].get<double>();
}

// The runs of every round, each round in the same order of edge lengths.
std::vector<std::vector<ScalingRun>> readScalingReport(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file + ": cannot read the scaling report");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    throw InputError(file + ": not a scaling report (not JSON)");
  }
  if (!j.is_object() || !j.contains("rounds") || !j["rounds"].is_array() || j["rounds"].empty())
    throw InputError(file + ": not a scaling report (no \"rounds\"; written by bench/scaling.py)");
  std::vector<std::vector<ScalingRun>> rounds;
  for (size_t r = 0; r < j["rounds"].size(); ++r) {
    const auto& round = j["rounds"][r];
    const std::string where = file + ": round " + std::to_string(r);
    if (!round.is_array() || round.empty()) throw InputError(where + " is not a list of runs");
    std::vector<ScalingRun> runs;
    for (size_t i = 0; i < round.size(); ++i) {
      const std::string at = where + " run " + std::to_string(i);
      if (!round[i].is_object()) throw InputError(at + " is not an object");
      runs.push_back({positive(round[i], "edge_cm", at), positive(round[i], "vertices", at),
                      positive(round[i], "wall_s", at), positive(round[i], "peak_mb", at)});
      if (!rounds.empty() && (rounds[0].size() <= i || rounds[0][i].edgeCm != runs.back().edgeCm))
        throw InputError(at + ": edge length " + std::to_string(runs.back().edgeCm) +
                         " cm differs from round 0's run " + std::to_string(i));
    }
    if (!rounds.empty() && runs.size() != rounds[0].size())
      throw InputError(where + " has " + std::to_string(runs.size()) + " runs, round 0 " +
                       std::to_string(rounds[0].size()));
    rounds.push_back(std::move(runs));
  }
  return rounds;
}

}  // namespace

int runScalingPlot(const CliOptions& options, std::ostream& out) {
  const std::filesystem::path file = options.output;
  if (file.extension() != ".png") throw InputError(file.string() + ": the scaling plot is written as .png");
  checkWritableDirectory(file);
  const auto rounds = readScalingReport(options.reports.at(0));
#ifdef DRAPE_WITH_GUI
  qt::TradeSeries time{"time to rest (s)", {}}, memory{"peak memory (MB)", {}};
  for (size_t i = 0; i < rounds[0].size(); ++i) {
    double wall = rounds[0][i].wallSeconds, peak = rounds[0][i].peakMb;
    for (const auto& round : rounds) {
      wall = std::min(wall, round[i].wallSeconds);
      peak = std::max(peak, round[i].peakMb);
    }
    char label[32];
    std::snprintf(label, sizeof label, "%g cm", rounds[0][i].edgeCm);
    // pareto: the line through the series' points.
    time.points.push_back({label, rounds[0][i].vertices, wall, true});
    memory.points.push_back({"", rounds[0][i].vertices, peak, true});
  }
  qt::writeTradePlot({time, memory}, "Drape cost against the mesh", file, 1200, 800,
                     {"garment vertices", "time to rest (s), peak memory (MB)"});
#else
  throw InputError(file.string() + ": this drape was built without Qt (DRAPE_BUILD_GUI=OFF), which draws the plot");
#endif
  out << "wrote " << file.string() << " (" << rounds[0].size() << " mesh sizes, " << rounds.size() << " rounds)\n";
  return 0;
}

}  // namespace drape::app
