#pragma once
// Every scene and solver setting under one dotted name ("mesh.target_edge_length", "avatar.units"), with its
// type, default, unit and valid range. Scene files and `--set key=value` both write through this registry,
// so an unknown key or a bad value gets the same clear error wherever it comes from, and the GUI and the
// benchmarks can list every setting.
#include <Eigen/Core>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace drape {

// Vector3: three numbers, written [x, y, z] in scene files and x,y,z on the command line.
enum class SettingType { Number, Integer, Boolean, Text, Choice, Vector3 };

// What a setting is about: the groups drape --list-settings and the GUI's settings table show, in this order.
enum class SettingGroup { Scene, Mesh, Fabric, Contact, Run, Preview, Drape, Quality, Output };
constexpr int kSettingGroupCount = 9;
const char* settingGroupName(SettingGroup group);   // "scene", "mesh", ...
const char* settingGroupTitle(SettingGroup group);  // one line on what the group's settings decide

// What a run simulates (solver.stage; in the order of the setting's choices): nothing (the placed garment), the
// preview, the drape from the placed garment, or the full pipeline (the preview, then the drape from its state).
enum class StagePlan { None, Preview, Drape, Full };

struct SettingSpec {
  std::string key;           // dotted name
  SettingType type;
  std::string defaultValue;  // textual; empty for an optional setting that is unset by default
  std::string unit;          // "m", "N/m", "" ...
  std::string description;
  double min = -1e300;       // Number/Integer bounds, and of each Vector3 component (inclusive)
  double max = 1e300;
  std::vector<std::string> choices;  // Choice only
  SettingGroup group = SettingGroup::Scene;
};

class Settings {
 public:
  Settings();  // every setting at its default

  static const std::vector<SettingSpec>& specs();
  static const SettingSpec* find(std::string_view key);
  // "a, b, c": every valid key, for error messages.
  static std::string validKeys();

  // Parses and checks value for key; context prefixes errors ("scene.json" or "--set").
  // Throws InputError for an unknown key (listing the valid ones), a mistyped or out-of-range value.
  void set(const std::string& key, const std::string& value, const std::string& context);

  bool has(std::string_view key) const;  // false for an optional setting left unset
  double number(std::string_view key) const;
  int integer(std::string_view key) const;
  bool flag(std::string_view key) const;
  const std::string& text(std::string_view key) const;
  Eigen::Vector3d vector3(std::string_view key) const;
  // A Choice setting as an enum whose enumerators are declared in the order of the spec's choices: the spec table
  // is the one place the names are written. choiceIndex: the value's position among the choices.
  int choiceIndex(std::string_view key) const;
  template <class Enum>
  Enum choice(std::string_view key) const {
    return static_cast<Enum>(choiceIndex(key));
  }
  StagePlan stagePlan() const { return choice<StagePlan>("solver.stage"); }

  // Settings that differ from their defaults, key -> value (for reports and saving).
  std::map<std::string, std::string> changed() const;

 private:
  const std::string& raw(std::string_view key) const;
  std::map<std::string, std::string, std::less<>> m_values;
};

}  // namespace drape
