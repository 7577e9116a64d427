#pragma once
// The speed <-> accuracy slider of the Simulation dock: each level sets the solver settings that trade one for
// the other (DESIGN.md section 1): the largest time step, the Newton and PCG tolerances and the mesh size.
#include <map>
#include <string>
#include <vector>

#include "drape/scene/settings.h"

namespace drape::qt {

struct SpeedAccuracyLevel {
  std::string name;                             // "Fastest" ... "Reference"
  std::map<std::string, std::string> settings;  // setting key -> value
};

// From fastest (index 0) to most accurate; "Balanced" (index 2) holds the paper defaults with a 2 cm mesh.
const std::vector<SpeedAccuracyLevel>& speedAccuracyLevels();

// The level whose settings are closest to settings (log distance over the level's keys).
int nearestSpeedAccuracyLevel(const Settings& settings);

}  // namespace drape::qt
