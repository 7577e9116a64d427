#include "drape/fabric/fabric.h"

#include <algorithm>

#include "core/json_reader.h"
#include "drape/core/assets.h"
#include "drape/core/input_error.h"

namespace drape {
namespace {

// Reads a positive (or non-negative) field within [lo, hi] with its unit in the message.
double bounded(const nlohmann::json& j, const std::string& key, const std::string& where, double lo, double hi,
               const char* unit) {
  const double v = json::number(j, key, where);
  if (v < lo || v > hi)
    throw InputError(where + ": field '" + key + "' = " + std::to_string(v) + " is outside [" + std::to_string(lo) +
                     ", " + std::to_string(hi) + "] " + unit);
  return v;
}

}  // namespace

std::filesystem::path fabricPresetDir() { return assetsDir() / "fabrics"; }

std::vector<std::string> fabricPresetNames(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

Fabric loadFabricFile(const std::filesystem::path& file) {
  const nlohmann::json j = json::parseFile(file);
  const std::string where = file.string();
  if (!j.is_object()) throw InputError(where + ": a fabric must be a JSON object");
  static const char* known[] = {"name",     "stretch_warp", "stretch_weft", "shear",     "bend_warp", "bend_weft",
                                "density",  "friction",     "thickness",    "damping",   "color",     "sources",
                                "description"};
  for (const auto& item : j.items()) {
    const std::string& key = item.key();
    if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return key == k; }) == std::end(known))
      throw InputError(where + ": unknown field '" + key + "'");
  }
  Fabric f;
  f.name = j.contains("name") ? json::text(j, "name", where) : file.stem().string();
  f.stretchWarp = bounded(j, "stretch_warp", where, 1e-3, 1e7, "N/m");
  f.stretchWeft = bounded(j, "stretch_weft", where, 1e-3, 1e7, "N/m");
  f.shear = bounded(j, "shear", where, 1e-4, 1e7, "N/m");
  f.bendWarp = bounded(j, "bend_warp", where, 0, 1, "N m");
  f.bendWeft = bounded(j, "bend_weft", where, 0, 1, "N m");
  f.density = bounded(j, "density", where, 1e-4, 10, "kg/m^2");
  f.friction = bounded(j, "friction", where, 0, 5, "");
  f.thickness = bounded(j, "thickness", where, 0, 0.05, "m");
  f.damping = bounded(j, "damping", where, 0, 10, "s");
  if (j.contains("color")) {
    const auto& c = j.at("color");
    if (!c.is_array() || c.size() != 3 || !std::all_of(c.begin(), c.end(), [](const auto& x) { return x.is_number(); }))
      throw InputError(where + ": field 'color' must be [r, g, b] with values in [0, 1]");
    for (int i = 0; i < 3; ++i) f.color[i] = std::clamp(c[i].get<float>(), 0.0f, 1.0f);
  }
  return f;
}

Fabric loadFabricPreset(const std::string& name, const std::filesystem::path& dir) {
  const auto names = fabricPresetNames(dir);
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError("unknown fabric preset '" + name + "'; available presets: " + (list.empty() ? "(none)" : list));
  }
  return loadFabricFile(dir / (name + ".json"));
}

}  // namespace drape
