// drape --list-settings, drape --list-fabrics.
#include <ostream>

#include "commands.h"
#include "drape/fabric/fabric.h"
#include "drape/scene/settings.h"

namespace drape::app {

int runListSettings(std::ostream& out) {
  for (const auto& spec : Settings::specs()) {
    out << spec.key << " = " << (spec.defaultValue.empty() ? "(unset)" : spec.defaultValue);
    if (!spec.unit.empty()) out << " [" << spec.unit << "]";
    const bool numeric = spec.type == SettingType::Number || spec.type == SettingType::Integer;
    if (numeric && spec.min > -1e299 && spec.max < 1e299) out << " (" << spec.min << " .. " << spec.max << ")";
    if (!spec.choices.empty()) {
      out << " {";
      for (size_t i = 0; i < spec.choices.size(); ++i) out << (i ? "|" : "") << spec.choices[i];
      out << "}";
    }
    out << "\n    " << spec.description << "\n";
  }
  return 0;
}

int runListFabrics(std::ostream& out) {
  for (const auto& name : fabricPresetNames()) {
    const Fabric f = loadFabricPreset(name);
    out << name << ": " << f.name << " (stretch " << f.stretchWarp << "/" << f.stretchWeft << " N/m, bend "
        << f.bendWarp << "/" << f.bendWeft << " N m, density " << f.density << " kg/m^2)\n";
  }
  return 0;
}

}  // namespace drape::app
