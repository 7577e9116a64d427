#include "drape/qt/speed_accuracy.h"

#include <cmath>
#include <limits>

#include "drape/core/assets.h"

namespace drape::qt {

const std::vector<SpeedAccuracyLevel>& speedAccuracyLevels() {
  static const std::vector<SpeedAccuracyLevel> levels =
      trade::readSpeedAccuracyLevels(assetsDir() / "trade" / "speed_accuracy_levels.json");
  return levels;
}

int nearestSpeedAccuracyLevel(const Settings& settings) {
  const auto& levels = speedAccuracyLevels();
  int best = 0;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < levels.size(); ++i) {
    double d = 0.0;
    for (const auto& [key, value] : levels[i].settings) {
      // Only numbers have a log distance (a level may also set a choice, e.g. a preconditioner).
      const SettingSpec* spec = Settings::find(key);
      if (!spec || (spec->type != SettingType::Number && spec->type != SettingType::Integer) || !settings.has(key))
        continue;
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
