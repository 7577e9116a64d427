#include "drape/avatar/body_measurements.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "drape/core/input_error.h"

namespace drape {
namespace {

constexpr double kCentimetre = 0.01;

// Key -> value (cm or degrees) read from the `body` map, or the top level when there is none.
using RawMeasurements = std::map<std::string, double>;

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& message) {
  throw InputError(file.filename().string() + ": " + message);
}

RawMeasurements readYaml(const std::filesystem::path& file) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    fail(file, std::string("not valid YAML: ") + e.what());
  }
  YAML::Node body = root.IsMap() && root["body"] ? root["body"] : root;
  if (!body.IsMap()) fail(file, "expected a map of body measurements under 'body'");
  RawMeasurements raw;
  for (const auto& entry : body) {
    if (!entry.first.IsScalar()) fail(file, "a key that is not a name (a list or a map)");
    const std::string key = entry.first.as<std::string>();
    if (!entry.second.IsScalar()) continue;
    try {
      raw[key] = entry.second.as<double>();
    } catch (const YAML::Exception&) {
      fail(file, "key '" + key + "': not a number ('" + entry.second.as<std::string>() + "')");
    }
  }
  return raw;
}

RawMeasurements readJson(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) fail(file, "cannot open file");
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    fail(file, std::string("not valid JSON: ") + e.what());
  }
  const nlohmann::json& body = root.is_object() && root.contains("body") ? root["body"] : root;
  if (!body.is_object()) fail(file, "expected an object of body measurements under 'body'");
  RawMeasurements raw;
  for (const auto& [key, value] : body.items()) {
    if (value.is_number()) {
      raw[key] = value.get<double>();
    } else if (!value.is_object() && !value.is_array() && !value.is_null()) {
      fail(file, "key '" + key + "': not a number (" + value.dump() + ")");
    }
  }
  return raw;
}

double required(const RawMeasurements& raw, const std::filesystem::path& file, const std::string& key) {
  auto it = raw.find(key);
  if (it == raw.end()) fail(file, "missing required key '" + key + "'");
  if (!std::isfinite(it->second) || it->second <= 0.0) {
    std::ostringstream s;
    s << "key '" << key << "' must be a positive length in cm (got " << it->second << ")";
    fail(file, s.str());
  }
  return it->second * kCentimetre;
}

std::optional<double> optionalLength(const RawMeasurements& raw, const std::filesystem::path& file,
                                     const std::string& key) {
  if (raw.find(key) == raw.end()) return std::nullopt;
  return required(raw, file, key);
}

}  // namespace

BodyMeasurements loadBodyMeasurements(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) fail(file, "file not found");
  std::string ext = file.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const RawMeasurements raw = ext == ".json" ? readJson(file) : readYaml(file);

  BodyMeasurements m;
  m.height = required(raw, file, "height");
  m.bust = required(raw, file, "bust");
  m.underbust = required(raw, file, "underbust");
  m.waist = required(raw, file, "waist");
  m.hips = required(raw, file, "hips");
  m.shoulderWidth = required(raw, file, "shoulder_w");
  m.neckWidth = required(raw, file, "neck_w");
  m.armLength = required(raw, file, "arm_length");
  m.wrist = required(raw, file, "wrist");
  m.thigh = required(raw, file, "leg_circ");
  auto angle = raw.find("arm_pose_angle");
  if (angle == raw.end()) fail(file, "missing required key 'arm_pose_angle'");
  if (!std::isfinite(angle->second) || angle->second < 0.0 || angle->second >= 90.0) {
    std::ostringstream s;
    s << "key 'arm_pose_angle' must be in [0, 90) degrees below the horizontal (got " << angle->second << ")";
    fail(file, s.str());
  }
  m.armPoseAngle = angle->second;
  m.headLength = optionalLength(raw, file, "head_l");
  m.waistLine = optionalLength(raw, file, "waist_line");
  m.hipsLine = optionalLength(raw, file, "hips_line");
  m.crotchHipDiff = optionalLength(raw, file, "crotch_hip_diff");
  m.vertBustLine = optionalLength(raw, file, "vert_bust_line");
  return m;
}

BodyMeasurements scaledBodyMeasurements(const BodyMeasurements& body, double scale) {
  BodyMeasurements m = body;
  for (double* length : {&m.height, &m.bust, &m.underbust, &m.waist, &m.hips, &m.shoulderWidth, &m.neckWidth,
                         &m.armLength, &m.wrist, &m.thigh})
    *length *= scale;
  for (std::optional<double>* length : {&m.headLength, &m.waistLine, &m.hipsLine, &m.crotchHipDiff, &m.vertBustLine})
    if (*length) **length *= scale;
  return m;
}

}  // namespace drape
