#pragma once
// The levels of the GUI's speed <-> accuracy slider, chosen from measurements. `drape --bench SCENE
// --levels` drapes every candidate of assets/trade/level_candidates.json and writes one trade report per scene;
// levelsFromReports keeps the candidates that no other candidate beats on both total wall time and total distance
// to the reference drapes, and `drape --trade-levels` writes them to assets/trade/speed_accuracy_levels.json, which
// the GUI reads with readSpeedAccuracyLevels.
#include <filesystem>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace drape::trade {

// The command that regenerates the levels file from the committed trade reports; its "generated_by".
inline constexpr std::string_view kLevelsCommand =
    "drape --trade-levels docs/trade/levels/*.json -o assets/trade/speed_accuracy_levels.json";

// One slider position, with what it costs and buys on the reference scene.
struct SpeedAccuracyLevel {
  std::string name;                             // "Fastest" ... "Reference"
  std::map<std::string, std::string> settings;  // setting key -> value
  double wallSeconds = 0.0;                     // wall time of the drape, s
  double distanceMm = 0.0;                      // mean vertex distance to the reference drape, mm
  bool atRest = false;                          // whether the drape came to rest (else it hit its time limit)
  std::string summary;                          // "about 4 s to rest, 1.2 mm from the reference on the default scene"
};

// The levels file (the format above) from trade reports, one per scene, each
//   {"name": "default", "scene": "...", "runs": [{"level": "Fast", "settings": {...}, "wall_time_s": 4.2,
//     "sim_time_s": 1.1, "mean_distance_mm": 1.2, "at_rest": true, ...}, ...], ...}
// in which the runs with a non-empty "level" are the candidates; every report has the same candidates with the
// same settings. Keeps the candidates on the Pareto front of (wall time summed over the reports, mean distance
// summed over the reports), fastest first; a kept level's wall_time_s, mean_distance_mm, at_rest and summary are
// those of the report named referenceScene, "scenes" holds every report's. A dropped candidate is listed with the
// fastest kept level that dominates it:
//   {"generated_by": kLevelsCommand, "reference_scene": "default",
//    "levels": [{"name", "settings", "wall_time_s", "mean_distance_mm", "at_rest", "summary",
//                "scenes": {"default": {"wall_time_s", "mean_distance_mm"}, ...}}, ...],
//    "dropped": [{"name", "dominated_by"}, ...]}
// Throws InputError naming the report (its "name") and the level for a candidate missing from a report, a report
// without candidates, a malformed run, or a referenceScene that no report has.
nlohmann::json levelsFromReports(const std::vector<nlohmann::json>& reports, const std::string& referenceScene);

// The levels of a file written from levelsFromReports, fastest first. Throws InputError naming the file and the
// element ("levels[1] ('Fast'): missing field 'summary'") for a missing file or bad content, including settings
// that the settings registry refuses.
std::vector<SpeedAccuracyLevel> readSpeedAccuracyLevels(const std::filesystem::path& file);

}  // namespace drape::trade
