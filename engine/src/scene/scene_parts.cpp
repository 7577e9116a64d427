#include "scene/scene_parts.h"

#include <cmath>
#include <cstdint>
#include <sstream>

#include "core/json_reader.h"
#include "drape/core/input_error.h"
#include "drape/geometry/primitives.h"

namespace drape {
namespace {

Eigen::Vector3d vec3(const nlohmann::json& j, const std::string& key, const std::string& where) {
  if (!j.contains(key)) throw InputError(where + ": missing field '" + key + "'");
  const auto& v = j.at(key);
  if (!v.is_array() || v.size() != 3) throw InputError(where + ": field '" + key + "' must be [x, y, z]");
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      throw InputError(where + ": field '" + key + "' must hold three finite numbers");
    out[i] = v[i].get<double>();
  }
  return out;
}

// Collider coordinates and sizes, metres: a scene is a few metres across; larger values are a unit mistake or
// garbage that would only make the contact search overflow.
constexpr double kMaxColliderExtent = 100.0;

std::string formatMetres(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

// vec3 with every coordinate within +-kMaxColliderExtent.
Eigen::Vector3d colliderPoint(const nlohmann::json& j, const std::string& key, const std::string& where) {
  const Eigen::Vector3d p = vec3(j, key, where);
  for (int i = 0; i < 3; ++i)
    if (std::abs(p[i]) > kMaxColliderExtent)
      throw InputError(where + ": field '" + key + "': " + "xyz"[i] + " = " + formatMetres(p[i]) +
                       " m is out of range [-" + formatMetres(kMaxColliderExtent) + ", " +
                       formatMetres(kMaxColliderExtent) + "] m");
  return p;
}

void rejectUnknown(const nlohmann::json& j, std::initializer_list<const char*> known, const std::string& where) {
  for (const auto& [key, value] : j.items()) {
    bool ok = false;
    std::string list;
    for (const char* k : known) {
      ok = ok || key == k;
      list += (list.empty() ? "" : ", ") + std::string(k);
    }
    if (!ok) throw InputError(where + ": unknown field '" + key + "'; valid fields: " + list);
  }
}

}  // namespace

Fabric resolveDefaultFabric(const Settings& settings) {
  Fabric f = loadFabricPreset(settings.text("fabric.preset"));
  struct Override {
    const char* key;
    double Fabric::*field;
  };
  static const Override overrides[] = {
      {"fabric.stretch_warp", &Fabric::stretchWarp},
      {"fabric.stretch_weft", &Fabric::stretchWeft},
      {"fabric.shear", &Fabric::shear},
      {"fabric.bend_warp", &Fabric::bendWarp},
      {"fabric.bend_weft", &Fabric::bendWeft},
      {"fabric.density", &Fabric::density},
      {"fabric.friction", &Fabric::friction},
      {"fabric.thickness", &Fabric::thickness},
      {"fabric.damping", &Fabric::damping},
  };
  for (const auto& o : overrides)
    if (settings.has(o.key)) f.*(o.field) = settings.number(o.key);
  return f;
}

std::map<std::string, Fabric> parsePanelFabrics(const nlohmann::json& j, const Pattern& pattern,
                                                const std::string& where) {
  if (!j.is_object()) throw InputError(where + ": 'panel_fabrics' must map panel names to fabric presets");
  std::map<std::string, Fabric> out;
  for (const auto& [panel, preset] : j.items()) {
    const std::string at = where + ": panel_fabrics '" + panel + "'";
    if (pattern.panelIndex(panel) < 0) throw InputError(at + ": the pattern has no panel of that name");
    if (!preset.is_string()) throw InputError(at + ": expected the name of a fabric preset");
    try {
      out[panel] = loadFabricPreset(preset.get<std::string>());
    } catch (const InputError& e) {
      throw InputError(at + ": " + e.what());
    }
  }
  return out;
}

std::vector<Collider> parseColliders(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array()) throw InputError(where + ": 'colliders' must be a list");
  std::vector<Collider> out;
  for (size_t i = 0; i < j.size(); ++i) {
    const auto& c = j[i];
    const std::string at = where + ": collider " + std::to_string(i);
    if (!c.is_object()) throw InputError(at + ": expected an object");
    const std::string type = json::text(c, "type", at);
    if (type == "sphere") {
      rejectUnknown(c, {"type", "center", "radius", "subdivisions"}, at);
      const double radius = json::number(c, "radius", at);
      if (radius <= 0) throw InputError(at + ": radius must be positive");
      if (radius > kMaxColliderExtent)
        throw InputError(at + ": radius " + formatMetres(radius) + " m is too large (at most " +
                         formatMetres(kMaxColliderExtent) + " m)");
      int subdivisions = 4;
      if (c.contains("subdivisions")) {
        subdivisions = static_cast<int>(json::number(c, "subdivisions", at));
        if (subdivisions < 0 || subdivisions > 7) throw InputError(at + ": subdivisions must be in [0, 7]");
      }
      out.push_back({"sphere", makeIcosphere(colliderPoint(c, "center", at), radius, subdivisions)});
    } else if (type == "box") {
      rejectUnknown(c, {"type", "min", "max"}, at);
      const Eigen::Vector3d lo = colliderPoint(c, "min", at), hi = colliderPoint(c, "max", at);
      if ((hi.array() <= lo.array()).any()) throw InputError(at + ": box 'max' must exceed 'min' on every axis");
      out.push_back({"box", makeBox(lo, hi)});
    } else {
      throw InputError(at + ": unknown collider type '" + type + "' (valid: sphere, box)");
    }
  }
  return out;
}

namespace {

double finiteNumber(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || !j.at(key).is_number() || !std::isfinite(j.at(key).get<double>()))
    throw InputError(where + ": '" + key + "' must be a number");
  return j.at(key).get<double>();
}

// "motion": {"start": s, "end": s, "rotate": {"axis": [..], "center": [..], "degrees": d}, "translate": [..]}
PinMotion parsePinMotion(const nlohmann::json& m, const std::string& where) {
  if (!m.is_object()) throw InputError(where + ": expected an object with 'start', 'end', 'rotate' and/or 'translate'");
  rejectUnknown(m, {"start", "end", "rotate", "translate"}, where);
  PinMotion motion;
  motion.start = finiteNumber(m, "start", where);
  motion.end = finiteNumber(m, "end", where);
  if (motion.end <= motion.start) throw InputError(where + ": 'end' must be after 'start'");
  if (!m.contains("rotate") && !m.contains("translate")) throw InputError(where + ": give 'rotate' and/or 'translate'");
  if (m.contains("rotate")) {
    const auto& r = m.at("rotate");
    const std::string at = where + " rotate";
    if (!r.is_object()) throw InputError(at + ": expected {\"axis\": [..], \"center\": [..], \"degrees\": d}");
    rejectUnknown(r, {"axis", "center", "degrees"}, at);
    motion.axis = vec3(r, "axis", at);
    if (motion.axis.norm() < 1e-12) throw InputError(at + ": 'axis' must not be zero");
    motion.axis.normalize();
    motion.center = vec3(r, "center", at);
    motion.angle = finiteNumber(r, "degrees", at) * M_PI / 180.0;
  }
  if (m.contains("translate")) motion.translation = vec3(m, "translate", where);
  return motion;
}

// "at": [[x, y, z], ...], one placed position (metres) per entry of the pin's "vertices".
std::vector<Eigen::Vector3d> parsePinPositions(const nlohmann::json& a, size_t count, const std::string& where) {
  if (!a.is_array())
    throw InputError(where + ": 'at' must be a list of [x, y, z] positions (metres), one per entry of 'vertices'");
  if (a.size() != count)
    throw InputError(where + ": 'at' has " + std::to_string(a.size()) + " positions but 'vertices' has " +
                     std::to_string(count) + " entries (one position per vertex)");
  std::vector<Eigen::Vector3d> out;
  for (size_t k = 0; k < a.size(); ++k) {
    const auto& e = a[k];
    const std::string at = where + ": at[" + std::to_string(k) + "]";
    if (!e.is_array() || e.size() != 3) throw InputError(at + " must be [x, y, z] (metres)");
    Eigen::Vector3d p;
    for (int i = 0; i < 3; ++i) {
      if (!e[i].is_number() || !std::isfinite(e[i].get<double>()))
        throw InputError(at + " must hold three finite numbers (metres)");
      p[i] = e[i].get<double>();
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace

std::vector<PinSpec> parsePins(const nlohmann::json& j, const Pattern& pattern, const std::string& where) {
  if (!j.is_array()) throw InputError(where + ": 'pins' must be a list");
  std::vector<PinSpec> out;
  for (size_t i = 0; i < j.size(); ++i) {
    const auto& p = j[i];
    PinSpec pin;
    pin.where = where + ": pin " + std::to_string(i);
    if (!p.is_object()) throw InputError(pin.where + ": expected an object");
    rejectUnknown(p, {"panel", "edge", "edge_label", "region", "vertices", "at", "motion"}, pin.where);
    const int kinds = int(p.contains("region")) + int(p.contains("panel")) + int(p.contains("vertices"));
    if (kinds != 1)
      throw InputError(pin.where + ": give exactly one of 'panel' (with an edge), 'region' or 'vertices'");
    if (p.contains("at") && !p.contains("vertices"))
      throw InputError(pin.where + ": 'at' belongs to a vertex pin (one position per entry of 'vertices')");
    if (p.contains("region")) {
      const auto& r = p.at("region");
      if (!r.is_object()) throw InputError(pin.where + ": 'region' must be {\"min\": [..], \"max\": [..]}");
      pin.byRegion = true;
      pin.region.min = vec3(r, "min", pin.where + " region");
      pin.region.max = vec3(r, "max", pin.where + " region");
      if ((pin.region.max.array() < pin.region.min.array()).any())
        throw InputError(pin.where + ": region 'max' is below 'min'");
    } else if (p.contains("vertices")) {
      const auto& vs = p.at("vertices");
      if (!vs.is_array() || vs.empty())
        throw InputError(pin.where + ": 'vertices' must be a non-empty list of indices");
      for (size_t k = 0; k < vs.size(); ++k) {
        if (!vs[k].is_number_integer() || vs[k].get<long long>() < 0 || vs[k].get<long long>() > INT32_MAX)
          throw InputError(pin.where + ": vertices[" + std::to_string(k) +
                           "] must be a vertex index (an integer >= 0)");
        pin.vertices.push_back(vs[k].get<int>());
      }
      if (p.contains("at")) pin.at = parsePinPositions(p.at("at"), pin.vertices.size(), pin.where);
    } else {
      pin.panel = json::text(p, "panel", pin.where);
      const int panel = pattern.panelIndex(pin.panel);
      if (panel < 0) throw InputError(pin.where + ": the pattern has no panel '" + pin.panel + "'");
      const int edgeCount = static_cast<int>(pattern.panels[panel].edges.size());
      if (p.contains("edge") == p.contains("edge_label"))
        throw InputError(pin.where + ": give exactly one of 'edge' (an index) or 'edge_label'");
      if (p.contains("edge")) {
        if (!p.at("edge").is_number_integer()) throw InputError(pin.where + ": 'edge' must be an integer");
        pin.edge = p.at("edge").get<int>();
        if (pin.edge < 0 || pin.edge >= edgeCount)
          throw InputError(pin.where + ": panel '" + pin.panel + "' has no edge " + std::to_string(pin.edge) +
                           " (it has " + std::to_string(edgeCount) + ")");
      } else {
        pin.edgeLabel = json::text(p, "edge_label", pin.where);
        const auto& edges = pattern.panels[panel].edges;
        auto it =
            std::find_if(edges.begin(), edges.end(), [&](const PanelEdge& e) { return e.label == pin.edgeLabel; });
        if (it == edges.end())
          throw InputError(pin.where + ": panel '" + pin.panel + "' has no edge labelled '" + pin.edgeLabel + "'");
        pin.edge = static_cast<int>(it - edges.begin());
      }
    }
    if (p.contains("motion")) {
      pin.moving = true;
      pin.motion = parsePinMotion(p.at("motion"), pin.where + " motion");
    }
    out.push_back(pin);
  }
  return out;
}

}  // namespace drape
