// drape --bench SCENE: the speed/accuracy trade of any setting in any stage, measured (docs/TRADE.md). The reference
// drape (trade::referenceConfig, the tightest setting) runs first, or is read from --reference when that file holds
// this scene's; then the scene's own settings ("default") and every --sweep value and --levels candidate, each alone
// over the scene's settings, in the --solver stage. Each run is reported against the reference: wall time, simulated
// time, steps, mean / 95th percentile / max distance from the reference's vertices to its final garment's surface (and
// the mean vertex to vertex distance on the reference's mesh), max strain, vertices inside a collider, whether it came
// to rest, the terms it used, and whether it is on the Pareto front of wall time against mean distance.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>

#include "commands.h"
#include "drape/core/assets.h"
#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"
#include "drape/scene/settings.h"
#include "drape/trade/pareto.h"
#include "drape/trade/trade_run.h"
#include "profile_json.h"
#include "trade_report.h"

namespace drape::app {
namespace {

using trade::SettingList;
using trade::TradeConfig;
using trade::TradeOutcome;

std::vector<std::string> splitCommas(const std::string& s) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t comma = s.find(',', start);
    out.push_back(s.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// The sweeps of a stage when none is given: the settings that trade speed for accuracy in it.
std::vector<std::pair<std::string, std::vector<std::string>>> defaultSweeps(const std::string& stage) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> drape = {
      {"solver.newton.h_max", {"5e-4", "2e-3", "4e-3"}},
      {"solver.newton.tolerance", {"1e-4", "1e-2"}},
      {"solver.cg.tolerance", {"1e-3", "1e-1"}}};
  const std::vector<std::pair<std::string, std::vector<std::string>>> preview = {
      {"solver.preview.time_step", {"0.004166666666666667", "0.016666666666666666"}},
      {"solver.preview.iterations", {"2", "8"}},
      {"solver.preview.domains", {"1", "4"}}};
  if (stage == "drape") return drape;
  if (stage == "preview") return preview;
  auto full = preview;
  full.insert(full.end(), drape.begin(), drape.end());
  return full;
}

// --sweep KEY=V1,V2,...: every value checked against the setting's type and range before anything runs.
std::vector<std::pair<std::string, std::vector<std::string>>> parseSweeps(const std::vector<std::string>& given) {
  std::vector<std::pair<std::string, std::vector<std::string>>> sweeps;
  for (const auto& s : given) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError("--sweep: '" + s + "' is not KEY=V1,V2,...");
    const std::string key = s.substr(0, eq);
    if (key == "solver.stage") throw InputError("--sweep: '" + s + "': the stage is chosen with --solver");
    const std::vector<std::string> values = splitCommas(s.substr(eq + 1));
    Settings check;
    for (const auto& v : values) {
      if (v.empty()) throw InputError("--sweep: '" + s + "' has an empty value");
      check.set(key, v, "--sweep");
    }
    sweeps.emplace_back(key, values);
  }
  return sweeps;
}

// The level candidates of the speed/accuracy slider (assets/trade/level_candidates.json), each a run.
std::vector<TradeConfig> levelConfigs(const std::string& stage) {
  const std::filesystem::path file = assetsDir() / "trade" / "level_candidates.json";
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot read the speed/accuracy level candidates");
  std::vector<TradeConfig> out;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    for (const auto& level : j.at("levels")) {
      TradeConfig c{"level " + level.at("name").get<std::string>(), level.at("name").get<std::string>(), stage, {}};
      Settings check;
      for (const auto& [k, v] : level.at("settings").items()) {
        check.set(k, v.get<std::string>(), file.string() + ": level '" + c.level + "'");
        c.settings.emplace_back(k, v.get<std::string>());
      }
      out.push_back(std::move(c));
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file.string() + ": " + e.what());
  }
  return out;
}

// "shirt_mean_specification on mean_all": the scene's name in reports and plots.
std::string sceneName(const SceneRequest& request) {
  std::string name = request.input.stem().string();
  if (!request.avatarFile.empty()) name += " on " + std::filesystem::path(request.avatarFile).stem().string();
  return name;
}

std::string formatSeconds(double s) {
  char b[32];
  std::snprintf(b, sizeof b, s < 100 ? "%.1f s" : "%.0f s", s);
  return b;
}

nlohmann::json runRow(const TradeOutcome& r, const trade::Distances& d) {
  nlohmann::json settings = nlohmann::json::object();
  for (const auto& [k, v] : r.config.settings) settings[k] = v;
  return {{"run", r.config.label},
          {"level", r.config.level},
          {"stage", r.config.stage},
          {"settings", settings},
          {"wall_time_s", r.wallSeconds},
          {"sim_time_s", r.simTime},
          {"steps", r.steps},
          {"status", r.status},
          {"at_rest", r.atRest()},
          {"mean_distance_mm", d.meanMm},
          {"p95_distance_mm", d.p95Mm},
          {"max_distance_mm", d.maxMm},
          {"vertex_mean_distance_mm", d.vertexMeanMm >= 0.0 ? nlohmann::json(d.vertexMeanMm) : nlohmann::json()},
          {"max_strain", r.maxStrain},
          {"inside_vertices", r.insideVertices},
          {"vertices", r.garment.vertexCount()},
          {"terms", r.terms},
          {"profile", profileJson(r.profile)}};
}

}  // namespace

int runBench(const CliOptions& options, std::ostream& out) {
  if (options.extremes) return runExtremes(options, out);
  const std::string stage = options.solver.empty() ? "drape" : options.solver;
  if (stage == "none") throw InputError("--bench: --solver none simulates nothing to measure");
  auto sweeps = parseSweeps(options.sweeps);
  if (sweeps.empty() && !options.levels) sweeps = defaultSweeps(stage);
  if (!options.plot.empty()) checkPlotPath(options.plot);
  if (!options.output.empty()) checkWritableDirectory(options.output);
  if (!options.reference.empty()) checkWritableDirectory(options.reference);

  SceneRequest base = options.scene;
  if (options.maxSimTime > 0) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.17g", options.maxSimTime);
    base.overrides.emplace_back("solver.max_sim_time", seconds);
  }
  std::vector<TradeConfig> configs = {{"default", "", stage, {}}};
  for (const auto& [key, values] : sweeps)
    for (const auto& v : values) configs.push_back({key + "=" + v, "", stage, {{key, v}}});
  if (options.levels)
    for (auto& c : levelConfigs(stage)) configs.push_back(std::move(c));

  // A reference must resolve what the runs resolve: on the finest mesh among the runs' (surface distances to it).
  TradeConfig referenceConfig = trade::referenceConfig();
  std::string finest;
  for (const TradeConfig& c : configs)
    for (const auto& [k, v] : c.settings)
      if (k == "mesh.target_edge_length" && (finest.empty() || std::stod(v) < std::stod(finest))) finest = v;
  if (!finest.empty() && std::stod(finest) < loadScene(base).settings.number("mesh.target_edge_length"))
    referenceConfig.settings.emplace_back("mesh.target_edge_length", finest);
  const std::string key = trade::referenceKey(base, referenceConfig);
  const bool kept = !options.reference.empty() && std::filesystem::exists(options.reference);
  // Every run --rounds times, the rounds interleaved (each round runs every setting once), so that a drift of the
  // machine's speed reaches every setting alike; a run's wall time is its fastest round's.
  const int rounds = options.rounds;
  const size_t total = configs.size() * rounds + (kept ? 0 : 1);
  size_t done = 0;
  const auto start = std::chrono::steady_clock::now();
  auto progress = [&](const TradeOutcome& r) {
    ++done;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    char line[256];
    std::snprintf(line, sizeof line, "[%zu/%zu] %s: %s, %s, %s elapsed, about %s left\n", done, total,
                  r.config.label.c_str(), formatSeconds(r.wallSeconds).c_str(), r.status.c_str(),
                  formatSeconds(elapsed).c_str(), formatSeconds(elapsed / done * (total - done)).c_str());
    out << line << std::flush;
  };
  TradeOutcome reference;
  if (kept) {
    reference = trade::readReference(options.reference, key);
    out << "reference: " << options.reference << " (" << formatSeconds(reference.wallSeconds) << ", "
        << reference.status << ")\n";
  } else {
    out << "[0/" << total << "] the reference drape (" << total << " runs in all)\n" << std::flush;
    reference = trade::runTrade(base, referenceConfig);
    progress(reference);
    // A reference that did not finish its drape measures nothing and is not kept.
    if (!options.reference.empty() && (reference.status == "AtRest" || reference.status == "MaxSimTime"))
      trade::writeReference(options.reference, reference, key);
  }
  std::vector<TradeOutcome> runs = {reference};
  std::vector<std::vector<double>> walls = {{reference.wallSeconds}};
  for (int round = 0; round < rounds; ++round)
    for (size_t c = 0; c < configs.size(); ++c) {
      TradeOutcome r = trade::runTrade(base, configs[c]);
      progress(r);
      if (round == 0) {
        runs.push_back(std::move(r));
        walls.push_back({runs.back().wallSeconds});
      } else {
        walls[c + 1].push_back(r.wallSeconds);
        runs[c + 1].wallSeconds = std::min(runs[c + 1].wallSeconds, r.wallSeconds);
      }
    }

  std::vector<trade::Distances> distances;
  std::vector<std::pair<double, double>> points;
  for (const auto& r : runs) {
    distances.push_back(trade::distanceToReference(r.garment, reference.garment));
    points.emplace_back(r.wallSeconds, distances.back().meanMm);
  }
  const std::vector<bool> front = trade::paretoFront(points);
  // Rows in the plot's order: by wall time.
  std::vector<size_t> order(runs.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return runs[a].wallSeconds < runs[b].wallSeconds; });

  nlohmann::json referenceSettings = nlohmann::json::object();
  for (const auto& [k, v] : referenceConfig.settings) referenceSettings[k] = v;
  nlohmann::json report = {{"scene", options.scene.input.string()},
                           {"name", sceneName(options.scene)},
                           {"stage", stage},
                           {"rounds", rounds},
                           {"reference",
                            {{"settings", referenceSettings},
                             {"stage", referenceConfig.stage},
                             {"wall_time_s", reference.wallSeconds},
                             {"sim_time_s", reference.simTime},
                             {"status", reference.status},
                             {"vertices", reference.garment.vertexCount()},
                             {"file", options.reference}}},
                           {"runs", nlohmann::json::array()}};
  char line[512];
  std::snprintf(line, sizeof line, "%-44s %-7s %9s %8s %6s %8s %8s %8s %8s %8s %6s %-10s %s\n", "run", "stage",
                "wall s", "sim s", "steps", "mean mm", "p95 mm", "max mm", "vtx mm", "strain %", "inside", "status",
                "front");
  out << line;
  for (size_t i : order) {
    const TradeOutcome& r = runs[i];
    const trade::Distances& d = distances[i];
    char vertexMean[16] = "-";
    if (d.vertexMeanMm >= 0.0) std::snprintf(vertexMean, sizeof vertexMean, "%.2f", d.vertexMeanMm);
    std::snprintf(line, sizeof line, "%-44s %-7s %9.2f %8.3f %6d %8.2f %8.2f %8.2f %8s %8.1f %6d %-10s %s\n",
                  r.config.label.c_str(), r.config.stage.c_str(), r.wallSeconds, r.simTime, r.steps, d.meanMm, d.p95Mm,
                  d.maxMm, vertexMean, 100 * r.maxStrain, r.insideVertices, r.status.c_str(), front[i] ? "yes" : "");
    out << line;
    nlohmann::json row = runRow(r, d);
    row["wall_times_s"] = walls[i];
    row["pareto"] = static_cast<bool>(front[i]);
    report["runs"].push_back(row);
  }
  if (!options.output.empty()) writeFileAtomically(options.output, report.dump(2) + "\n");
  if (!options.plot.empty()) plotTradeReports({report}, options.plot);
  if (reference.status != "AtRest" && reference.status != "MaxSimTime") {
    out << "drape --bench: the reference drape ended " << reference.status << " at t = " << reference.simTime
        << " s, so the distances above are to its last good state and not meaningful\n";
    return 1;
  }
  return 0;
}

}  // namespace drape::app
