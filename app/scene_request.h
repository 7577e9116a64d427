#pragma once
// The scene request of a headless mode with the command line's stage options folded into --set overrides.
#include <iosfwd>
#include <string>
#include <vector>

#include "cli_options.h"

namespace drape::app {

// --solver (simulate) or --simulate (render) become solver.stage; --max-sim-time becomes solver.max_sim_time.
SceneRequest requestWithStage(const CliOptions& options);

// One "warning: ..." line per warning (loader, mesher and avatar warnings of --simulate and --render; --info lists
// them in its own summary).
void printWarnings(const std::vector<std::string>& warnings, std::ostream& out);

}  // namespace drape::app
