// drape --list-settings, drape --list-fabrics.
#include <ostream>

#include "commands.h"
#include "drape/fabric/fabric.h"
#include "drape/scene/settings.h"

namespace drape::app {

// The settings by group (the table's order), each group under a heading "[name] what it decides".
int runListSettings(std::ostream& out) {
  for (size_t i = 0; i < Settings::specs().size(); ++i) {
    const SettingSpec& spec = Settings::specs()[i];
    if (i == 0 || Settings::specs()[i - 1].group != spec.group)
      out << (i ? "\n" : "") << "[" << settingGroupName(spec.group) << "] " << settingGroupTitle(spec.group) << "\n";
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
