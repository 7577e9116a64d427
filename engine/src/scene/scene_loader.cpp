#include <algorithm>

#include "core/json_reader.h"
#include "drape/avatar/avatar_loader.h"
#include "drape/core/input_error.h"
#include "drape/pattern/dxf_aama.h"
#include "drape/pattern/pattern_loader.h"
#include "drape/scene/scene.h"
#include "scene/scene_parts.h"

namespace drape {
namespace {

// Top-level keys with their own structure.
const char* kStructuredKeys[] = {"pattern", "colliders", "pins", "panel_fabrics", "name", "description"};

bool isOneOf(const std::string& key, const char* const* begin, const char* const* end) {
  return std::find_if(begin, end, [&](const char* k) { return key == k; }) != end;
}

bool isSettingSection(const std::string& key) {
  const auto& sections = sceneSettingSections();
  return std::find(sections.begin(), sections.end(), key) != sections.end();
}

// Writes the leaves of object into settings under prefix.
void flattenInto(const nlohmann::json& object, const std::string& prefix, Settings& settings, const std::string& where) {
  for (const auto& [key, value] : object.items()) {
    const std::string dotted = prefix + "." + key;
    if (value.is_object()) {
      flattenInto(value, dotted, settings, where);
    } else if (value.is_array()) {
      // [x, y, z] for vector settings.
      std::string text;
      for (const auto& item : value) text += (text.empty() ? "" : ",") + json::scalarText(item, where + ": '" + dotted + "'");
      settings.set(dotted, text, where);
    } else {
      settings.set(dotted, json::scalarText(value, where + ": '" + dotted + "'"), where);
    }
  }
}

std::string listOf(const char* const* begin, const char* const* end) {
  std::string s;
  for (auto it = begin; it != end; ++it) s += (s.empty() ? "" : ", ") + std::string(*it);
  return s;
}

std::string listOf(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& name : names) s += (s.empty() ? "" : ", ") + name;
  return s;
}

std::filesystem::path resolveRelative(const std::filesystem::path& base, const std::string& path) {
  std::filesystem::path p(path);
  return p.is_absolute() ? p : base / p;
}

}  // namespace

const std::vector<std::string>& sceneSettingSections() {
  // Sections whose leaves are settings ("mesh": {"target_edge_length": 0.02} -> mesh.target_edge_length).
  static const std::vector<std::string> sections = {"avatar", "fabric",  "mesh",    "placement", "sim",
                                                    "solver", "contact", "quality", "camera",    "render"};
  return sections;
}

bool isPatternFile(const std::filesystem::path& file) {
  if (isDxfFile(file)) return true;
  const nlohmann::json j = json::parseFile(file, json::DuplicateKeys::Allow);
  return j.is_object() && j.contains("pattern") && j.at("pattern").is_object();
}

Scene loadScene(const SceneRequest& request) {
  Scene scene;
  scene.file = request.input;
  const std::string where = request.input.string();
  std::string text;
  // A DXF-AAMA file is a bare pattern; anything else is JSON.
  const nlohmann::json j = isDxfFile(request.input)
                               ? nlohmann::json{{"pattern", nlohmann::json::object()}}
                               : json::parseFile(request.input, json::DuplicateKeys::Allow, &text);
  if (!j.is_object()) throw InputError(where + ": expected a JSON object (a scene or a pattern)");
  const bool barePattern = j.contains("pattern") && j.at("pattern").is_object();
  // A repeated key would silently override a setting; a bare pattern gets the pattern loader's own check.
  if (!barePattern) json::refuseDuplicateKeys(text, where);
  const std::filesystem::path base = request.input.parent_path();

  nlohmann::json colliders, pins, panelFabrics;
  if (barePattern) {
    scene.settings.set("pattern", request.input.string(), where);
  } else {
    for (const auto& [key, value] : j.items()) {
      if (isSettingSection(key)) {
        if (key == "fabric" && value.is_string()) {
          scene.settings.set("fabric.preset", value.get<std::string>(), where);
        } else if (key == "avatar" && value.is_string()) {
          scene.settings.set("avatar.file", value.get<std::string>(), where);
        } else if (key == "avatar" && value.is_null()) {
          continue;
        } else if (!value.is_object()) {
          throw InputError(where + ": '" + key + "' must be an object");
        } else {
          flattenInto(value, key, scene.settings, where);
        }
      } else if (key == "pattern") {
        if (!value.is_string()) throw InputError(where + ": 'pattern' must be the path of a pattern file");
        scene.settings.set("pattern", value.get<std::string>(), where);
      } else if (key == "colliders") {
        colliders = value;
      } else if (key == "pins") {
        pins = value;
      } else if (key == "panel_fabrics") {
        panelFabrics = value;
      } else if (!isOneOf(key, std::begin(kStructuredKeys), std::end(kStructuredKeys))) {
        throw InputError(where + ": unknown key '" + key +
                         "'; valid keys: " + listOf(std::begin(kStructuredKeys), std::end(kStructuredKeys)) + ", " +
                         listOf(sceneSettingSections()));
      }
    }
    if (!scene.settings.has("pattern") || scene.settings.text("pattern").empty())
      throw InputError(where + ": missing 'pattern' (the path of a sewing pattern file)");
  }

  // Paths in the scene file are relative to it; command-line paths to the working directory.
  if (!barePattern && scene.settings.has("avatar.file") && !scene.settings.text("avatar.file").empty())
    scene.settings.set("avatar.file", resolveRelative(base, scene.settings.text("avatar.file")).string(), where);
  if (!barePattern)
    scene.settings.set("pattern", resolveRelative(base, scene.settings.text("pattern")).string(), where);
  if (!request.avatarFile.empty()) scene.settings.set("avatar.file", request.avatarFile, "--avatar");
  if (!request.avatarUnits.empty()) scene.settings.set("avatar.units", request.avatarUnits, "--avatar-units");
  if (!request.fabricPreset.empty()) scene.settings.set("fabric.preset", request.fabricPreset, "--fabric");
  for (const auto& [key, value] : request.overrides) scene.settings.set(key, value, "--set " + key);

  // Errors in the files the scene names carry the scene file as a prefix.
  auto within = [&](const char* part, const auto& load) {
    try {
      load();
    } catch (const InputError& e) {
      throw InputError(where + ": " + part + ": " + e.what());
    }
  };
  scene.patternFile = scene.settings.text("pattern");
  if (barePattern) scene.pattern = loadPattern(scene.patternFile, &scene.diagnostics);
  else within("pattern", [&] { scene.pattern = loadPattern(scene.patternFile, &scene.diagnostics); });
  // A graded size scales every pattern length (panel outlines and placements) alike: fewer pattern units per metre.
  scene.pattern.unitsInMeter /= scene.settings.number("grading.scale");

  if (scene.settings.has("avatar.file") && !scene.settings.text("avatar.file").empty()) {
    scene.avatarFile = scene.settings.text("avatar.file");
    within("avatar", [&] {
      scene.avatar = loadAvatar(scene.avatarFile, unitsInMeterFromName(scene.settings.text("avatar.units")),
                                &scene.diagnostics);
    });
  }

  within("fabric", [&] { scene.fabric = resolveDefaultFabric(scene.settings); });
  if (!panelFabrics.is_null()) scene.panelFabrics = parsePanelFabrics(panelFabrics, scene.pattern, where);
  if (!colliders.is_null()) scene.colliders = parseColliders(colliders, where);
  if (!pins.is_null()) scene.pins = parsePins(pins, scene.pattern, where);
  return scene;
}

}  // namespace drape
