// Writing a drape::Pattern in GarmentCode's JSON layout, the inverse of pattern_loader.cpp.
#include "drape/pattern/pattern_writer.h"

#include <cmath>
#include <set>
#include <stdexcept>

#include "drape/io/atomic_file.h"
#include "pattern/json_fields.h"

namespace drape {
namespace {

using detail::Json;

// A value whose one-line form fits before this column is written on one line (vertex lists, edges, stitches).
constexpr size_t kLineWidth = 120;

[[noreturn]] void refuse(const std::string& where, const std::string& problem) {
  throw std::invalid_argument("cannot save the pattern: " + (where.empty() ? problem : where + ": " + problem));
}

Json number(double x, const std::string& where, const std::string& what) {
  if (!std::isfinite(x)) refuse(where, what + " is not finite (" + std::to_string(x) + ")");
  return Json(x);  // nlohmann writes the shortest text that reads back as the same double
}

Json point(const Eigen::Vector2d& p, const std::string& where, const std::string& what) {
  return Json::array({number(p.x(), where, what), number(p.y(), where, what)});
}

Json points(const std::vector<Eigen::Vector2d>& ps, const std::string& where, const std::string& what) {
  Json out = Json::array();
  for (size_t i = 0; i < ps.size(); ++i) out.push_back(point(ps[i], where, what + " " + std::to_string(i)));
  return out;
}

Json curvature(const EdgeCurve& curve, const std::string& where) {
  const size_t expected = curve.type == CurveType::Quadratic ? 1 : curve.type == CurveType::Cubic ? 2 : 0;
  if (curve.controls.size() != expected)
    refuse(where, "the curve needs " + std::to_string(expected) + " control points, has " +
                      std::to_string(curve.controls.size()));
  switch (curve.type) {
    case CurveType::Straight: return nullptr;
    case CurveType::Quadratic:
      return Json{{"type", "quadratic"}, {"params", points(curve.controls, where, "control point")}};
    case CurveType::Cubic: return Json{{"type", "cubic"}, {"params", points(curve.controls, where, "control point")}};
    case CurveType::Circle:
      return Json{{"type", "circle"},
                  {"params", Json::array({number(curve.radius, where, "circle radius"), curve.largeArc, curve.right})}};
  }
  refuse(where, "unknown curve type");
}

Json panelJson(const Panel& panel) {
  const std::string where = "panel '" + panel.name + "'";
  Json pj;
  pj["vertices"] = points(panel.vertices, where, "vertex");
  Json edges = Json::array();
  const int nv = int(panel.vertices.size());
  for (size_t i = 0; i < panel.edges.size(); ++i) {
    const PanelEdge& edge = panel.edges[i];
    const std::string ew = where + " edge " + std::to_string(i);
    if (edge.start < 0 || edge.start >= nv || edge.end < 0 || edge.end >= nv)
      refuse(ew, "endpoints " + std::to_string(edge.start) + ", " + std::to_string(edge.end) + " out of range (" +
                     std::to_string(nv) + " vertices)");
    Json ej;
    ej["endpoints"] = Json::array({edge.start, edge.end});
    if (Json c = curvature(edge.curve, ew); !c.is_null()) ej["curvature"] = std::move(c);
    if (!edge.label.empty()) ej["label"] = edge.label;
    edges.push_back(std::move(ej));
  }
  pj["edges"] = std::move(edges);
  pj["translation"] = Json::array();
  pj["rotation"] = Json::array();
  for (int k = 0; k < 3; ++k) {
    pj["translation"].push_back(number(panel.translation[k], where, "translation"));
    pj["rotation"].push_back(number(panel.rotationDeg[k], where, "rotation"));
  }
  if (!panel.label.empty()) pj["label"] = panel.label;
  if (panel.grainLine)
    pj["grainline"] = points({(*panel.grainLine)[0], (*panel.grainLine)[1]}, where, "grainline point");
  if (!panel.notches.empty()) pj["notches"] = points(panel.notches, where, "notch");
  if (!panel.internalLines.empty()) {
    Json lines = Json::array();
    for (size_t k = 0; k < panel.internalLines.size(); ++k) {
      const std::string line = "internal line " + std::to_string(k);
      if (panel.internalLines[k].size() < 2)
        refuse(where, line + " has " + std::to_string(panel.internalLines[k].size()) + " points (at least 2)");
      lines.push_back(points(panel.internalLines[k], where, line + " point"));
    }
    pj["internal_lines"] = std::move(lines);
  }
  return pj;
}

Json stitchSide(const Pattern& pattern, const StitchSide& side, const std::string& where) {
  if (side.panel < 0 || side.panel >= int(pattern.panels.size()))
    refuse(where, "panel index " + std::to_string(side.panel) + " out of range");
  const Panel& panel = pattern.panels[side.panel];
  if (side.edge < 0 || side.edge >= int(panel.edges.size()))
    refuse(where, "panel '" + panel.name + "' has no edge " + std::to_string(side.edge));
  return Json{{"panel", panel.name}, {"edge", side.edge}};
}

Json patternJson(const Pattern& pattern) {
  Json panels = Json::object();
  Json order = Json::array();
  std::set<std::string> names;
  for (const Panel& panel : pattern.panels) {
    if (!names.insert(panel.name).second) refuse("", "two panels are called '" + panel.name + "'");
    panels[panel.name] = panelJson(panel);
    order.push_back(panel.name);
  }
  Json stitches = Json::array();
  for (size_t k = 0; k < pattern.stitches.size(); ++k) {
    const Stitch& stitch = pattern.stitches[k];
    const std::string where = "stitch " + std::to_string(k);
    Json sj = Json::array({stitchSide(pattern, stitch.a, where), stitchSide(pattern, stitch.b, where)});
    if (stitch.rightWrong) sj.push_back("right_wrong");
    stitches.push_back(std::move(sj));
  }
  Json root;
  root["pattern"] = Json{{"panels", std::move(panels)}, {"stitches", std::move(stitches)}, {"panel_order", order}};
  // normalize_panel_translation = false: GarmentCode takes the translations as written, as Drape does.
  root["properties"] = Json{{"units_in_meter", number(pattern.unitsInMeter, "properties", "units_in_meter")},
                            {"curvature_coords", "relative"},
                            {"normalize_panel_translation", false}};
  return root;
}

// JSON text on one line, with a space after ',' and ':'.
std::string oneLine(const Json& value) {
  if (value.is_object()) {
    std::string out = "{";
    for (auto it = value.begin(); it != value.end(); ++it)
      out += (it == value.begin() ? "" : ", ") + Json(it.key()).dump() + ": " + oneLine(it.value());
    return out + "}";
  }
  if (value.is_array()) {
    std::string out = "[";
    for (size_t i = 0; i < value.size(); ++i) out += (i ? ", " : "") + oneLine(value[i]);
    return out + "]";
  }
  return value.dump();
}

// Appends value starting at column `column` of a line indented by `indent`: on one line when it fits, else one
// member or element per line.
void appendLaidOut(const Json& value, size_t indent, size_t column, std::string& out) {
  const std::string flat = oneLine(value);
  if (!value.is_structured() || value.empty() || column + flat.size() <= kLineWidth) {
    out += flat;
    return;
  }
  const std::string inner(indent + 2, ' ');
  out += value.is_object() ? "{\n" : "[\n";
  size_t i = 0;
  for (auto it = value.begin(); it != value.end(); ++it, ++i) {
    out += inner;
    size_t col = inner.size();
    if (value.is_object()) {
      const std::string key = Json(it.key()).dump() + ": ";
      out += key;
      col += key.size();
    }
    appendLaidOut(it.value(), indent + 2, col, out);
    out += i + 1 < value.size() ? ",\n" : "\n";
  }
  out += std::string(indent, ' ') + (value.is_object() ? "}" : "]");
}

}  // namespace

std::string patternToJson(const Pattern& pattern) {
  try {
    std::string out;
    appendLaidOut(patternJson(pattern), 0, 0, out);
    return out + "\n";
  } catch (const Json::exception& e) {  // a name or label that is not valid UTF-8
    refuse("", e.what());
  }
}

void savePattern(const Pattern& pattern, const std::filesystem::path& file) {
  writeFileAtomically(file, patternToJson(pattern));
}

}  // namespace drape
