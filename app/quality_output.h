#pragma once
// The quality verdict of --simulate and --render --simulate (sim/drape_quality.h): one warning line per failed
// check, its --stats object, and the exit status it gives.
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>

#include "drape/sim/drape_quality.h"

namespace drape::app {

// Exit status of a run whose verdict failed.
constexpr int kQualityFailedExit = 4;
// Exit status of a run whose solver diverged (the last good state is still written).
constexpr int kDivergedExit = 3;

// One "warning: quality: ..." line per failed check.
void printQualityWarnings(const QualityReport& report, std::ostream& out);
// {"passed": bool, "checks": {name: {"value", "threshold", "passed", and "vertex", "triangle", "other_triangle",
// "where" where the check has them}}}.
nlohmann::json qualityJson(const QualityReport& report);
// 3 when the run diverged, 4 when the verdict failed, else 0.
int simulatedExitStatus(const std::string& status, const QualityReport& report);

}  // namespace drape::app
