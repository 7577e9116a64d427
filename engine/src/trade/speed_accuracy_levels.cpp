#include "drape/trade/speed_accuracy_levels.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>

#include "core/json_reader.h"
#include "drape/core/input_error.h"
#include "drape/scene/settings.h"
#include "drape/trade/pareto.h"

namespace drape::trade {
namespace {

// One candidate's run in one trade report.
struct Candidate {
  std::string level;
  std::map<std::string, std::string> settings;
  double wallSeconds = 0.0;
  double simSeconds = 0.0;
  double distanceMm = 0.0;
  bool atRest = false;
};

struct Report {
  std::string name;   // the scene's short name, "default"
  std::string where;  // "trade report 'default' (assets/scenes/default.json)", for messages
  std::vector<Candidate> candidates;
  const Candidate* find(const std::string& level) const {
    for (const Candidate& c : candidates)
      if (c.level == level) return &c;
    return nullptr;
  }
};

double nonNegative(const nlohmann::json& j, const std::string& key, const std::string& where) {
  const double v = json::number(j, key, where);
  if (v < 0) throw InputError(where + ": field '" + key + "' = " + std::to_string(v) + " is negative");
  return v;
}

bool flag(const nlohmann::json& j, const std::string& key, const std::string& where) {
  if (!j.contains(key)) throw InputError(where + ": missing field '" + key + "'");
  if (!j.at(key).is_boolean()) throw InputError(where + ": field '" + key + "' must be true or false");
  return j.at(key).get<bool>();
}

const nlohmann::json& settingsObject(const nlohmann::json& j, const std::string& where) {
  if (!j.contains("settings")) throw InputError(where + ": missing field 'settings'");
  const nlohmann::json& s = j.at("settings");
  if (!s.is_object() || s.empty()) throw InputError(where + ": field 'settings' must be a non-empty object");
  return s;
}

Report readReport(const nlohmann::json& j, size_t index, size_t count) {
  const std::string numbered = "trade report " + std::to_string(index + 1) + " of " + std::to_string(count);
  if (!j.is_object()) throw InputError(numbered + ": must be a JSON object");
  Report report;
  report.name = json::text(j, "name", numbered);
  if (report.name.empty()) throw InputError(numbered + ": field 'name' is empty");
  report.where = "trade report '" + report.name + "'";
  if (j.contains("scene") && j.at("scene").is_string()) report.where += " (" + j.at("scene").get<std::string>() + ")";
  if (!j.contains("runs") || !j.at("runs").is_array())
    throw InputError(report.where + ": field 'runs' must be an array");
  const nlohmann::json& runs = j.at("runs");
  for (size_t k = 0; k < runs.size(); ++k) {
    const nlohmann::json& run = runs[k];
    const std::string at = report.where + ": runs[" + std::to_string(k) + "]";
    if (!run.is_object()) throw InputError(at + ": must be a JSON object");
    if (!run.contains("level")) continue;  // the reference
    Candidate c;
    c.level = json::text(run, "level", at);
    if (c.level.empty()) continue;
    const std::string where = report.where + ": level '" + c.level + "'";
    if (report.find(c.level)) throw InputError(where + ": appears twice");
    for (const auto& [key, value] : settingsObject(run, where).items())
      c.settings[key] = json::scalarText(value, where + ": setting '" + key + "'");
    c.wallSeconds = nonNegative(run, "wall_time_s", where);
    c.simSeconds = nonNegative(run, "sim_time_s", where);
    c.distanceMm = nonNegative(run, "mean_distance_mm", where);
    c.atRest = flag(run, "at_rest", where);
    report.candidates.push_back(std::move(c));
  }
  if (report.candidates.empty())
    throw InputError(report.where +
                     ": no candidate runs (no run has a \"level\"); measure the candidates with drape --bench SCENE "
                     "--levels");
  return report;
}

// Every report has the first one's candidates with its settings, and no others.
void checkSameCandidates(const std::vector<Report>& reports) {
  const Report& first = reports.front();
  for (const Report& r : reports) {
    for (const Candidate& c : first.candidates) {
      const Candidate* here = r.find(c.level);
      if (!here) throw InputError(r.where + ": no run of level '" + c.level + "' (" + first.where + " has one)");
      if (here->settings != c.settings)
        throw InputError(r.where + ": level '" + c.level + "' was measured with other settings than in " + first.where +
                         " (the reports come from different candidate files)");
    }
    for (const Candidate& c : r.candidates)
      if (!first.find(c.level)) throw InputError(r.where + ": level '" + c.level + "' is not in " + first.where);
  }
}

// "4" for 4.2, "0.84" for 0.84: whole units from `whole` up, else two significant digits.
std::string rounded(double x, double whole) {
  if (x >= whole) return std::to_string(std::lround(x));
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", x);
  return text;
}

std::string summary(const Candidate& c, const std::string& scene) {
  std::string s = "about " + rounded(c.wallSeconds, 3) + " s";
  s += c.atRest ? " to rest" : " (" + rounded(c.simSeconds, 3) + " s simulated, not at rest)";
  return s + ", " + rounded(c.distanceMm, 10) + " mm from the reference on the " + scene + " scene";
}

bool dominates(const std::pair<double, double>& a, const std::pair<double, double>& b) {
  return a.first <= b.first && a.second <= b.second && (a.first < b.first || a.second < b.second);
}

}  // namespace

nlohmann::json levelsFromReports(const std::vector<nlohmann::json>& reports, const std::string& referenceScene) {
  if (reports.empty()) throw InputError("trade levels: no trade reports given");
  std::vector<Report> parsed;
  std::set<std::string> names;
  for (size_t i = 0; i < reports.size(); ++i) {
    parsed.push_back(readReport(reports[i], i, reports.size()));
    if (!names.insert(parsed.back().name).second)
      throw InputError(parsed.back().where + ": a second report named '" + parsed.back().name + "'");
  }
  checkSameCandidates(parsed);
  const auto reference =
      std::find_if(parsed.begin(), parsed.end(), [&](const Report& r) { return r.name == referenceScene; });
  if (reference == parsed.end()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError("trade levels: reference scene '" + referenceScene + "' has no trade report (reports: " + list +
                     ")");
  }

  // Costs summed over the scenes, in the candidate order of the first report.
  const std::vector<Candidate>& candidates = parsed.front().candidates;
  std::vector<std::pair<double, double>> totals(candidates.size(), {0.0, 0.0});
  for (size_t i = 0; i < candidates.size(); ++i)
    for (const Report& r : parsed) {
      const Candidate* c = r.find(candidates[i].level);
      totals[i].first += c->wallSeconds;
      totals[i].second += c->distanceMm;
    }
  const std::vector<bool> front = paretoFront(totals);
  std::vector<size_t> kept;
  for (size_t i = 0; i < candidates.size(); ++i)
    if (front[i]) kept.push_back(i);
  std::stable_sort(kept.begin(), kept.end(), [&](size_t a, size_t b) { return totals[a].first < totals[b].first; });

  nlohmann::json out = {{"generated_by", std::string(kLevelsCommand)},
                        {"reference_scene", referenceScene},
                        {"levels", nlohmann::json::array()},
                        {"dropped", nlohmann::json::array()}};
  for (size_t i : kept) {
    const Candidate& c = *reference->find(candidates[i].level);
    nlohmann::json scenes = nlohmann::json::object();
    for (const Report& r : parsed) {
      const Candidate* here = r.find(c.level);
      scenes[r.name] = {{"wall_time_s", here->wallSeconds}, {"mean_distance_mm", here->distanceMm}};
    }
    out["levels"].push_back({{"name", c.level},
                             {"settings", c.settings},
                             {"wall_time_s", c.wallSeconds},
                             {"mean_distance_mm", c.distanceMm},
                             {"at_rest", c.atRest},
                             {"summary", summary(c, referenceScene)},
                             {"scenes", scenes}});
  }
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (front[i]) continue;
    // A point off the front is dominated by one on it; name the fastest such.
    const auto by = std::find_if(kept.begin(), kept.end(), [&](size_t k) { return dominates(totals[k], totals[i]); });
    assert(by != kept.end());
    out["dropped"].push_back({{"name", candidates[i].level}, {"dominated_by", candidates[*by].level}});
  }
  return out;
}

std::vector<SpeedAccuracyLevel> readSpeedAccuracyLevels(const std::filesystem::path& file) {
  const nlohmann::json j = json::parseFile(file);
  const std::string where = file.string();
  if (!j.is_object()) throw InputError(where + ": must be a JSON object");
  if (!j.contains("levels") || !j.at("levels").is_array() || j.at("levels").empty())
    throw InputError(where + ": field 'levels' must be a non-empty array");
  std::vector<SpeedAccuracyLevel> levels;
  std::set<std::string> names;
  const nlohmann::json& items = j.at("levels");
  for (size_t i = 0; i < items.size(); ++i) {
    std::string at = where + ": levels[" + std::to_string(i) + "]";
    const nlohmann::json& item = items[i];
    if (!item.is_object()) throw InputError(at + ": must be a JSON object");
    SpeedAccuracyLevel level;
    level.name = json::text(item, "name", at);
    if (level.name.empty()) throw InputError(at + ": field 'name' is empty");
    at += " ('" + level.name + "')";
    if (!names.insert(level.name).second) throw InputError(at + ": a second level of this name");
    Settings probe;  // the registry checks key and value as for a scene file
    for (const auto& [key, value] : settingsObject(item, at).items()) {
      if (!value.is_string()) throw InputError(at + ": setting '" + key + "' must be a string");
      probe.set(key, value.get<std::string>(), at);
      level.settings[key] = value.get<std::string>();
    }
    level.wallSeconds = nonNegative(item, "wall_time_s", at);
    level.distanceMm = nonNegative(item, "mean_distance_mm", at);
    level.atRest = flag(item, "at_rest", at);
    level.summary = json::text(item, "summary", at);
    levels.push_back(std::move(level));
  }
  return levels;
}

}  // namespace drape::trade
