#include "batch_manifest_reader.h"

#include <algorithm>

#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"
#include "drape/core/input_error.h"
#include "drape/fabric/fabric.h"
#include "drape/scene/settings.h"

namespace drape::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

bool isMeasurementFile(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".yaml" || ext == ".yml" || ext == ".json";
}

}  // namespace

std::string joinedList(const std::vector<std::string>& items, const char* separator) {
  std::string text;
  for (const auto& item : items) text += (text.empty() ? "" : separator) + item;
  return text;
}

bool listContains(const std::vector<std::string>& items, const std::string& item) {
  return std::find(items.begin(), items.end(), item) != items.end();
}

ManifestReader::ManifestReader(const fs::path& manifest)
    : m_name(manifest.string()), m_base(fs::absolute(manifest).parent_path()) {}

void ManifestReader::fail(const std::string& element, const std::string& what) const {
  throw InputError(m_name + ": " + element + ": " + what);
}

void ManifestReader::checkKeys(const json& object, const std::string& prefix,
                               const std::vector<std::string>& valid) const {
  for (const auto& item : object.items())
    if (!listContains(valid, item.key()))
      fail(prefix + item.key(), "unknown key (valid keys: " + joinedList(valid) + ")");
}

std::string ManifestReader::text(const json& value, const std::string& element) const {
  if (!value.is_string() || value.get<std::string>().empty()) fail(element, "must be a non-empty string");
  return value.get<std::string>();
}

const json& ManifestReader::list(const json& value, const std::string& element) const {
  if (!value.is_array()) fail(element, "must be a list");
  if (value.empty()) fail(element, "empty list");
  return value;
}

BatchInput ManifestReader::file(const json& value, const std::string& element) const {
  BatchInput input{text(value, element), {}};
  input.file = (fs::path(input.text).is_absolute() ? fs::path(input.text) : m_base / input.text).lexically_normal();
  std::error_code ec;
  if (!fs::is_regular_file(input.file, ec)) fail(element, "file not found: " + input.file.string());
  return input;
}

void ManifestReader::avatar(const json& value, const std::string& element, BatchJob& job) const {
  job.avatar = file(value, element);
  job.avatarIsMeasurements = isMeasurementFile(job.avatar.file);
  job.avatarMesh = job.avatar.file;
  if (!job.avatarIsMeasurements) return;
  try {
    mannequinLevels(loadBodyMeasurements(job.avatar.file));  // the checks makeMannequin makes before meshing
  } catch (const InputError& e) {
    fail(element, e.what());
  }
}

void ManifestReader::mannequinOf(const fs::path& measurements, double scale, const std::string& element) const {
  try {
    mannequinLevels(scaledBodyMeasurements(loadBodyMeasurements(measurements), scale));
  } catch (const InputError& e) {
    fail(element, e.what());
  }
}

std::string ManifestReader::fabric(const json& value, const std::string& element) const {
  const std::string name = text(value, element);
  const auto presets = fabricPresetNames();
  if (!listContains(presets, name))
    fail(element, "unknown fabric preset '" + name + "' (presets: " + joinedList(presets) + ")");
  return name;
}

SettingOverrides ManifestReader::overrides(const json& value, const std::string& element) const {
  if (!value.is_array()) fail(element, "must be a list of \"KEY=VALUE\" strings");
  SettingOverrides result;
  for (size_t i = 0; i < value.size(); ++i) {
    const std::string at = element + "[" + std::to_string(i) + "]";
    const std::string kv = text(value[i], at);
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) fail(at, "'" + kv + "' is not KEY=VALUE");
    const std::string key = kv.substr(0, eq);
    if (!Settings::find(key)) fail(at, "unknown setting '" + key + "' (see drape --list-settings)");
    result.emplace_back(key, kv.substr(eq + 1));
  }
  return result;
}

}  // namespace drape::app
