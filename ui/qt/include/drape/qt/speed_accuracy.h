#pragma once
// The speed <-> accuracy slider of the Simulation dock: each level sets the solver settings that trade one for
// the other (DESIGN.md section 1): the largest time step, the Newton and PCG tolerances and the mesh size. The
// levels are the measured candidates on the speed/accuracy Pareto front (assets/trade/speed_accuracy_levels.json,
// written by `drape --trade-levels`; see drape/trade/speed_accuracy_levels.h).
#include <vector>

#include "drape/scene/settings.h"
#include "drape/trade/speed_accuracy_levels.h"

namespace drape::qt {

using trade::SpeedAccuracyLevel;

// From fastest (index 0) to most accurate, read once from assetsDir() / "trade/speed_accuracy_levels.json".
// Throws InputError naming the file and the element when it is missing or bad (and tries again on the next call).
const std::vector<SpeedAccuracyLevel>& speedAccuracyLevels();

// The level whose settings are closest to settings (log distance over the level's numeric keys). Throws as
// speedAccuracyLevels().
int nearestSpeedAccuracyLevel(const Settings& settings);

}  // namespace drape::qt
