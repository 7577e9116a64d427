#include "quality_output.h"

#include <ostream>

namespace drape::app {

void printQualityWarnings(const QualityReport& report, std::ostream& out) {
  for (const QualityCheck& c : report.checks)
    if (!c.passed) out << "warning: quality: " << c.message << "\n";
}

nlohmann::json qualityJson(const QualityReport& report) {
  nlohmann::json checks = nlohmann::json::object();
  for (const QualityCheck& c : report.checks) {
    nlohmann::json j = {{"value", c.value}, {"threshold", c.threshold}, {"passed", c.passed}};
    if (c.vertex >= 0) j["vertex"] = c.vertex;
    if (c.triangle >= 0) j["triangle"] = c.triangle;
    if (c.otherTriangle >= 0) j["other_triangle"] = c.otherTriangle;
    if (!c.where.empty()) j["where"] = c.where;
    checks[c.name] = j;
  }
  return {{"passed", report.passed}, {"checks", checks}};
}

int simulatedExitStatus(const std::string& status, const QualityReport& report) {
  if (status == "Diverged") return kDivergedExit;
  return report.passed ? 0 : kQualityFailedExit;
}

}  // namespace drape::app
