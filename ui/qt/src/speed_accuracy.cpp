#include "drape/qt/speed_accuracy.h"

#include <cmath>
#include <limits>

namespace drape::qt {

const std::vector<SpeedAccuracyLevel>& speedAccuracyLevels() {
  // Values around the paper defaults (newton-drape-pizana: h_max = 1 ms, tau_n = 1e-3, tau_cg = 1e-2).
  static const std::vector<SpeedAccuracyLevel> levels = {
      {"Fastest",
       {{"solver.newton.h_max", "0.004"},
        {"solver.newton.tolerance", "0.01"},
        {"solver.cg.tolerance", "0.1"},
        {"mesh.target_edge_length", "0.04"}}},
      {"Fast",
       {{"solver.newton.h_max", "0.002"},
        {"solver.newton.tolerance", "0.003"},
        {"solver.cg.tolerance", "0.05"},
        {"mesh.target_edge_length", "0.03"}}},
      {"Balanced",
       {{"solver.newton.h_max", "0.001"},
        {"solver.newton.tolerance", "0.001"},
        {"solver.cg.tolerance", "0.01"},
        {"mesh.target_edge_length", "0.02"}}},
      {"Accurate",
       {{"solver.newton.h_max", "0.0005"},
        {"solver.newton.tolerance", "0.0003"},
        {"solver.cg.tolerance", "0.001"},
        {"mesh.target_edge_length", "0.012"}}},
      {"Reference",
       {{"solver.newton.h_max", "0.00025"},
        {"solver.newton.tolerance", "0.0001"},
        {"solver.cg.tolerance", "0.0001"},
        {"mesh.target_edge_length", "0.008"}}},
  };
  return levels;
}

int nearestSpeedAccuracyLevel(const Settings& settings) {
  const auto& levels = speedAccuracyLevels();
  int best = 0;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < levels.size(); ++i) {
    double d = 0.0;
    for (const auto& [key, value] : levels[i].settings) {
      const double here = settings.number(key), there = std::stod(value);
      if (here > 0 && there > 0) d += std::abs(std::log(here / there));
    }
    if (d < bestDistance) {
      bestDistance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace drape::qt
