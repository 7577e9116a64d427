#include "scene_request.h"

#include <ostream>
#include <sstream>

namespace drape::app {

SceneRequest requestWithStage(const CliOptions& options) {
  SceneRequest request = options.scene;
  const std::string& stage = options.mode == Mode::Render ? options.simulateStage : options.solver;
  if (!stage.empty()) {
    request.overrides.insert(request.overrides.begin(), {"solver.stage", stage});
  }
  if (options.maxSimTime > 0) {
    std::ostringstream os;
    os.precision(17);
    os << options.maxSimTime;
    request.overrides.emplace_back("solver.max_sim_time", os.str());
  }
  return request;
}

void printWarnings(const std::vector<std::string>& warnings, std::ostream& out) {
  for (const std::string& w : warnings) out << "warning: " << w << "\n";
}

}  // namespace drape::app
