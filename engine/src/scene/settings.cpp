#include "drape/scene/settings.h"

#include <map>
#include <charconv>
#include <cmath>
#include <sstream>

#include "drape/core/input_error.h"

namespace drape {
namespace {

std::string describe(const SettingSpec& spec) {
  switch (spec.type) {
    case SettingType::Number: return "a number";
    case SettingType::Integer: return "an integer";
    case SettingType::Boolean: return "true or false";
    case SettingType::Text: return "text";
    case SettingType::Vector3: return "three numbers x,y,z";
    case SettingType::Choice: {
      std::string s = "one of";
      for (const auto& c : spec.choices) s += " " + c;
      return s;
    }
  }
  return "a value";
}

bool parseNumber(const std::string& text, double& out) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  auto [ptr, ec] = std::from_chars(begin, end, out);
  return ec == std::errc() && ptr == end && std::isfinite(out);
}

// Canonical form of value for spec, or throws.
std::string canonical(const SettingSpec& spec, const std::string& value, const std::string& context) {
  auto fail = [&](const std::string& why) {
    throw InputError(context + ": setting '" + spec.key + "': " + why);
  };
  switch (spec.type) {
    case SettingType::Number:
    case SettingType::Integer: {
      double v = 0;
      if (!parseNumber(value, v)) fail("'" + value + "' is not " + describe(spec));
      if (spec.type == SettingType::Integer && v != std::floor(v)) fail("'" + value + "' is not an integer");
      if (v < spec.min || v > spec.max) {
        std::ostringstream os;
        os << value << " is out of range [" << spec.min << ", " << spec.max << "]"
           << (spec.unit.empty() ? "" : " " + spec.unit);
        fail(os.str());
      }
      return value;
    }
    case SettingType::Boolean:
      if (value == "true" || value == "1" || value == "on") return "true";
      if (value == "false" || value == "0" || value == "off") return "false";
      fail("'" + value + "' is not true or false");
      break;
    case SettingType::Choice:
      for (const auto& c : spec.choices)
        if (c == value) return value;
      fail("'" + value + "' is not " + describe(spec));
      break;
    case SettingType::Text: return value;
    case SettingType::Vector3: {
      std::string canon;
      size_t start = 0;
      for (int i = 0; i < 3; ++i) {
        const size_t comma = value.find(',', start);
        if ((i < 2) != (comma != std::string::npos)) fail("'" + value + "' is not " + describe(spec));
        std::string part = value.substr(start, i < 2 ? comma - start : std::string::npos);
        part.erase(0, part.find_first_not_of(' '));
        part.erase(part.find_last_not_of(' ') + 1);
        double v = 0;
        if (!parseNumber(part, v)) fail("'" + value + "' is not " + describe(spec));
        if (v < spec.min || v > spec.max) {
          std::ostringstream os;
          os << "'" << value << "': "
             << "xyz"[i] << " = " << part << " is out of range [" << spec.min << ", " << spec.max << "]"
             << (spec.unit.empty() ? "" : " " + spec.unit);
          fail(os.str());
        }
        canon += (i ? "," : "") + part;
        start = comma + 1;
      }
      return canon;
    }
  }
  return value;
}

}  // namespace

Settings::Settings() {
  for (const auto& spec : specs())
    if (!spec.defaultValue.empty()) m_values[spec.key] = spec.defaultValue;
}

const SettingSpec* Settings::find(std::string_view key) {
  for (const auto& spec : specs())
    if (spec.key == key) return &spec;
  return nullptr;
}

std::string Settings::validKeys() {
  std::string list;
  for (const auto& spec : specs()) list += (list.empty() ? "" : ", ") + spec.key;
  return list;
}

// Settings that were replaced: a scene that names one is told what to write instead.
const std::map<std::string, std::string>& retiredSettings() {
  static const std::map<std::string, std::string> retired = {
      {"solver.newton.early_stop_threshold",
       "solver.newton.rest_speed (m/s, the 99th percentile of vertex speeds; a kinetic energy in J stopped a light or "
       "finely meshed garment while it still moved)"},
      {"solver.damping.stretch", "fabric.damping (the fabric's own stretch dissipation)"}};
  return retired;
}

void Settings::set(const std::string& key, const std::string& value, const std::string& context) {
  const SettingSpec* spec = find(key);
  if (!spec && retiredSettings().count(key))
    throw InputError(context + ": the setting '" + key + "' is replaced by " + retiredSettings().at(key));
  if (!spec) throw InputError(context + ": unknown setting '" + key + "'; valid settings: " + validKeys());
  if (value.empty() && spec->defaultValue.empty()) {
    m_values.erase(spec->key);  // back to unset
    return;
  }
  m_values[spec->key] = canonical(*spec, value, context);
}

bool Settings::has(std::string_view key) const { return m_values.find(key) != m_values.end(); }

const std::string& Settings::raw(std::string_view key) const {
  auto it = m_values.find(key);
  if (it == m_values.end()) {
    static const std::string empty;
    if (!find(key)) throw std::logic_error("Settings: no setting named " + std::string(key));
    return empty;
  }
  return it->second;
}

double Settings::number(std::string_view key) const {
  const std::string& v = raw(key);
  if (v.empty()) throw std::logic_error("Settings: " + std::string(key) + " is unset");
  return std::stod(v);
}

int Settings::integer(std::string_view key) const { return static_cast<int>(std::lround(number(key))); }

bool Settings::flag(std::string_view key) const { return raw(key) == "true"; }

Eigen::Vector3d Settings::vector3(std::string_view key) const {
  const std::string& v = raw(key);
  if (v.empty()) throw std::logic_error("Settings: " + std::string(key) + " is unset");
  Eigen::Vector3d out;
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = v.find(',', start);
    out[i] = std::stod(v.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    start = comma + 1;
  }
  return out;
}

const std::string& Settings::text(std::string_view key) const { return raw(key); }

std::map<std::string, std::string> Settings::changed() const {
  std::map<std::string, std::string> out;
  for (const auto& spec : specs()) {
    auto it = m_values.find(spec.key);
    const std::string value = it == m_values.end() ? "" : it->second;
    if (value != spec.defaultValue) out[spec.key] = value;
  }
  return out;
}

}  // namespace drape
