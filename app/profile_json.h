#pragma once
// Where a simulation's wall time went (sim/simulation.h, PhaseProfile), as the JSON object of --stats and of
// --bench's runs.
#include <nlohmann/json.hpp>

#include "drape/sim/simulation.h"

namespace drape::app {

// {"assembly_s", "linear_solve_s", "contact_queries_s", "line_search_s", "bookkeeping_s", "steps_s"}: seconds, the
// last their sum.
nlohmann::json profileJson(const PhaseProfile& profile);

}  // namespace drape::app
