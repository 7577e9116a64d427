#pragma once
// The scene request of a headless mode with the command line's stage options folded into --set overrides.
#include "cli_options.h"

namespace drape::app {

// --solver (simulate) or --simulate (render) become solver.stage; --max-sim-time becomes solver.max_sim_time.
SceneRequest requestWithStage(const CliOptions& options);

}  // namespace drape::app
