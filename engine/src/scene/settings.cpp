#include "drape/scene/settings.h"

#include <charconv>
#include <cmath>
#include <map>
#include <set>
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

const char* settingGroupName(SettingGroup group) {
  switch (group) {
    case SettingGroup::Scene: return "scene";
    case SettingGroup::Mesh: return "mesh";
    case SettingGroup::Fabric: return "fabric";
    case SettingGroup::Contact: return "contact";
    case SettingGroup::Run: return "run";
    case SettingGroup::Preview: return "preview";
    case SettingGroup::Drape: return "drape";
    case SettingGroup::Quality: return "quality";
    case SettingGroup::Output: return "output";
  }
  return "";
}

const char* settingGroupTitle(SettingGroup group) {
  switch (group) {
    case SettingGroup::Scene: return "the pattern, the body, where the garment starts, gravity";
    case SettingGroup::Mesh: return "how the panels are meshed and sewn";
    case SettingGroup::Fabric: return "the fabric preset and overrides of its properties";
    case SettingGroup::Contact: return "contact with the body and the cloth itself, friction";
    case SettingGroup::Run: return "what a run simulates and for how long";
    case SettingGroup::Preview: return "the fast preview (the drape's model by L-BFGS, pd-dd's system as its initial Hessian)";
    case SettingGroup::Drape: return "the accurate drape (Backward-Euler Newton, its PCG, damping, stitches, pins)";
    case SettingGroup::Quality: return "the verdict on every simulated result";
    case SettingGroup::Output: return "renders: the camera";
  }
  return "";
}

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
      {"solver.damping.stretch", "fabric.damping (the fabric's own stretch dissipation)"},
      {"solver.preview.qn_time_step", "solver.preview.time_step"},
      {"solver.preview.qn_iterations", "solver.preview.iterations"}};
  return retired;
}

// Switches between implementations of one computation that agree to round-off or to the solver's tolerance: no
// longer scene settings; the benchmarks that measure them set them (Scene::implementation).
const std::map<std::string, std::string>& implementationSwitches() {
  static const std::map<std::string, std::string> switches = {
      {"solver.newton.block_map", "map"},  {"solver.newton.fold_dissipation", "fold"},
      {"solver.newton.batched_gradients", "batch"}, {"solver.cg.fused_kernels", "fused"},
      {"solver.newton.closed_form_bending", "bending"}, {"solver.newton.parallel_assembly", "parallel"},
      {"solver.newton.reorder_dofs", "reorder"}, {"solver.preview.global_solver", ""}};
  return switches;
}

// Settings of the projective preview, which is no longer a stage of the simulation: the preview solves the drape's
// own model (DESIGN.md 5a), and pd-dd's projective solver is a library component measured by its benchmark.
static bool projectivePreviewSetting(const std::string& key) {
  static const std::set<std::string> removed = {
      "solver.preview.method", "solver.preview.tolerance", "solver.preview.max_iterations",
      "solver.preview.anderson_window", "solver.preview.max_halvings", "solver.preview.grow_after_steps",
      "solver.preview.local_step", "solver.preview.contact_solve", "solver.preview.pcg_tolerance",
      "solver.preview.hold_contact_targets", "solver.preview.hold_targets_step", "solver.preview.sewn_gap",
      "solver.preview.sewn_time", "solver.preview.sewn_local_step", "solver.preview.assembly_edge_length",
      "solver.preview.contact_targets", "solver.preview.friction_load", "solver.preview.shear_model",
      "solver.preview.failure_strain", "solver.preview.relaxation_time", "solver.preview.courant_limit",
      "solver.preview.pipeline_courant_limit", "solver.preview.softened_max_time", "solver.preview.retry_courant_limit",
      "solver.preview.retry_without_held_targets", "solver.preview.handoff_strain", "solver.preview.sd_iterations",
      "solver.preview.ccd", "solver.preview.rest_speed"};
  return removed.count(key) > 0;
}

void Settings::set(const std::string& key, const std::string& value, const std::string& context) {
  const SettingSpec* spec = find(key);
  if (!spec && projectivePreviewSetting(key))
    throw InputError(context + ": '" + key + "' was a setting of the projective preview, which is gone: the preview " +
                     "solves the drape's own model (solver.preview.time_step, iterations, domains, max_time, " +
                     "handoff_speed; docs/ENGINE.md)");
  if (!spec && retiredSettings().count(key))
    throw InputError(context + ": the setting '" + key + "' is replaced by " + retiredSettings().at(key));
  if (!spec && implementationSwitches().count(key)) {
    const std::string& feature = implementationSwitches().at(key);
    throw InputError(context + ": '" + key + "' is no longer a setting: it switches between implementations that " +
                     "give the same drape, and its benchmark measures it (" +
                     (feature.empty() ? std::string("the domain-decomposed solve against monolithic CHOLMOD, "
                                                    "docs/BENCHMARKS.md")
                                      : "build/bench/drape_newton_bench --configs on-" + feature) +
                     ")");
  }
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

int Settings::choiceIndex(std::string_view key) const {
  const SettingSpec* spec = find(key);
  if (!spec || spec->type != SettingType::Choice)
    throw std::logic_error("Settings: " + std::string(key) + " is not a choice");
  const std::string& value = raw(key);
  for (size_t i = 0; i < spec->choices.size(); ++i)
    if (spec->choices[i] == value) return static_cast<int>(i);
  throw std::logic_error("Settings: " + std::string(key) + " holds no choice");
}

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
