// Reading a GarmentCode JSON pattern into drape::Pattern; structure here, geometric checks in
// pattern_validation.cpp, curvature in curvature_parser.cpp. Format: docs/FORMATS.md "Pattern files".
#include "drape/pattern/pattern_loader.h"

#include "core/json_reader.h"

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "drape/core/input_error.h"
#include "drape/pattern/dxf_aama.h"
#include "pattern/curvature_parser.h"
#include "pattern/json_fields.h"
#include "pattern/pattern_validation.h"

namespace drape {
namespace {

using detail::Json;
using detail::JsonFields;

// nlohmann keeps the last of repeated keys, so a second panel of the same name would replace the first.
void refuseDuplicateKeys(const std::string& jsonText, const JsonFields& f) {
  const auto duplicate = json::findDuplicateKey(jsonText);
  if (!duplicate) return;
  const std::vector<std::string>& path = duplicate->path;
  const bool inPanels = path.size() >= 2 && path[0] == "pattern" && path[1] == "panels";
  if (inPanels && path.size() == 2) f.fail("", "panel '" + duplicate->key + "' defined twice");
  if (inPanels) {
    json::DuplicateKey inPanel{{path.begin() + 3, path.end()}, duplicate->key};
    f.fail("panel '" + path[2] + "'", "key '" + inPanel.dotted() + "' appears twice");
  }
  f.fail("", "key '" + duplicate->dotted() + "' appears twice");
}

struct FileProperties {
  double unitsInMeter = 100.0;
  bool absoluteCurvature = false;
};

FileProperties readProperties(const Json& root, const JsonFields& f, Diagnostics& diagnostics) {
  FileProperties props;
  const auto it = root.find("properties");
  if (it == root.end()) {
    diagnostics.warn(f.source() +
                     ": no 'properties'; assuming units_in_meter 100 (centimetres) and relative "
                     "curvature coordinates");
    return props;
  }
  f.expectObject(*it, "", "'properties'");
  if (const auto units = it->find("units_in_meter"); units != it->end()) {
    if (!units->is_number())
      f.fail("properties", "bad units: units_in_meter must be a number, got " + detail::describeType(*units));
    props.unitsInMeter = units->get<double>();
    if (!std::isfinite(props.unitsInMeter) || props.unitsInMeter <= 0.0)
      f.fail("properties", "bad units: units_in_meter must be a positive finite number, got " + units->dump());
  } else {
    diagnostics.warn(f.source() + ": properties has no units_in_meter; assuming 100 (centimetres)");
  }
  if (const auto coords = it->find("curvature_coords"); coords != it->end()) {
    const std::string value = f.readString(*coords, "properties", "curvature_coords");
    if (value == "absolute")
      props.absoluteCurvature = true;
    else if (value != "relative")
      f.fail("properties", "unknown curvature_coords '" + value + "' (expected \"relative\" or \"absolute\")");
  }
  return props;
}

// Reads the edges and checks they form one closed loop visiting each vertex at most once.
void readEdges(Panel& panel, const Json& edgesJson, const JsonFields& f, const FileProperties& props,
               Diagnostics& diagnostics) {
  const std::string where = "panel '" + panel.name + "'";
  f.expectArray(edgesJson, where, "'edges'");
  if (edgesJson.empty()) f.fail(where, "empty panel: 'edges' is empty");
  if (edgesJson.size() < 2) f.fail(where, "a panel needs at least 2 edges to close its outline, got 1");
  const int nv = int(panel.vertices.size());

  Eigen::AlignedBox2d box;
  for (const auto& v : panel.vertices) box.extend(v);
  const double tiny = 1e-9 * std::max(box.diagonal().norm(), 1e-300);

  for (size_t i = 0; i < edgesJson.size(); ++i) {
    const std::string ew = where + " edge " + std::to_string(i);
    const Json& ej = edgesJson[i];
    f.expectObject(ej, ew, "the edge");
    const Json& endpoints = f.member(ej, "endpoints", ew);
    if (!endpoints.is_array() || endpoints.size() != 2)
      f.fail(ew, "'endpoints' must be an array of 2 vertex indices, got " + detail::describeType(endpoints));
    PanelEdge edge;
    edge.start = f.readIndex(endpoints[0], ew, "endpoint");
    edge.end = f.readIndex(endpoints[1], ew, "endpoint");
    for (int v : {edge.start, edge.end})
      if (v >= nv)
        f.fail(ew, "endpoint " + std::to_string(v) + " out of range (panel has " + std::to_string(nv) + " vertices)");
    if (edge.start == edge.end) f.fail(ew, "zero-length edge: starts and ends at vertex " + std::to_string(edge.start));
    const Eigen::Vector2d& a = panel.vertices[edge.start];
    const Eigen::Vector2d& b = panel.vertices[edge.end];
    if ((b - a).norm() <= tiny)
      f.fail(ew, "zero-length edge: vertices " + std::to_string(edge.start) + " and " + std::to_string(edge.end) +
                     " are at the same position");
    if (const auto c = ej.find("curvature"); c != ej.end())
      edge.curve = detail::parseCurvature(*c, f, ew, props.absoluteCurvature, a, b);
    if (const auto label = ej.find("label"); label != ej.end()) edge.label = f.readString(*label, ew, "'label'");
    panel.edges.push_back(std::move(edge));
  }

  // One closed chain: each edge ends where the next starts, the last ends where the first starts.
  const int ne = int(panel.edges.size());
  for (int i = 0; i + 1 < ne; ++i) {
    if (panel.edges[i].end != panel.edges[i + 1].start)
      f.fail(where + " edge " + std::to_string(i),
             "open edge loop: edge ends at vertex " + std::to_string(panel.edges[i].end) + " but edge " +
                 std::to_string(i + 1) + " starts at vertex " + std::to_string(panel.edges[i + 1].start) +
                 " (edges must chain end -> start)");
  }
  if (panel.edges.back().end != panel.edges.front().start)
    f.fail(where + " edge " + std::to_string(ne - 1),
           "open edge loop: last edge ends at vertex " + std::to_string(panel.edges.back().end) +
               " but edge 0 starts at vertex " + std::to_string(panel.edges.front().start) + " (loop does not close)");
  std::map<int, int> startedBy;
  for (int i = 0; i < ne; ++i) {
    const auto [it, inserted] = startedBy.emplace(panel.edges[i].start, i);
    if (!inserted)
      f.fail(where + " edge " + std::to_string(i),
             "non-simple edge loop: vertex " + std::to_string(panel.edges[i].start) + " is visited twice (edges " +
                 std::to_string(it->second) + " and " + std::to_string(i) + " both start there)");
  }
  if (int(startedBy.size()) < nv) {
    std::string unused;
    for (int v = 0; v < nv; ++v)
      if (!startedBy.count(v)) unused += (unused.empty() ? "" : ", ") + std::to_string(v);
    diagnostics.warn(f.source() + ": " + where + ": vertices not on the edge loop are ignored: " + unused);
  }
}

// A marking point: finite, and not absurdly far from the panel (kMaxPanelExtent metres from its corners' box).
Eigen::Vector2d readMarkingPoint(const Json& value, const Panel& panel, const JsonFields& f, const std::string& what,
                                 double unitsInMeter) {
  const std::string where = "panel '" + panel.name + "'";
  const Eigen::Vector2d p = f.readVec2(value, where, what);
  Eigen::AlignedBox2d box;
  for (const auto& v : panel.vertices) box.extend(v);
  const double away = box.exteriorDistance(p) / unitsInMeter;
  if (!(away <= detail::kMaxPanelExtent)) {
    std::ostringstream distance;
    distance << std::setprecision(4) << away;
    f.fail(where, what + " " + value.dump() + " is " + distance.str() + " m from the panel's corners (at most " +
                      Json(detail::kMaxPanelExtent).dump() + " m)");
  }
  return p;
}

// The optional markings "grainline", "notches" and "internal_lines" (docs/FORMATS.md "Pattern files").
void readMarkings(Panel& panel, const Json& pj, const JsonFields& f, double unitsInMeter) {
  const std::string where = "panel '" + panel.name + "'";
  if (const auto it = pj.find("grainline"); it != pj.end()) {
    if (!it->is_array() || it->size() != 2)
      f.fail(where, "'grainline' must be [[x0, y0], [x1, y1]], got " + detail::describeType(*it));
    const Eigen::Vector2d from = readMarkingPoint((*it)[0], panel, f, "'grainline' point 0", unitsInMeter);
    const Eigen::Vector2d to = readMarkingPoint((*it)[1], panel, f, "'grainline' point 1", unitsInMeter);
    Eigen::AlignedBox2d box;
    for (const auto& v : panel.vertices) box.extend(v);
    if ((to - from).norm() <= 1e-9 * box.diagonal().norm())
      f.fail(where, "'grainline' has zero length (both points at " + (*it)[0].dump() + "): it gives no direction");
    panel.grainLine = std::array<Eigen::Vector2d, 2>{from, to};
  }
  if (const auto it = pj.find("notches"); it != pj.end()) {
    f.expectArray(*it, where, "'notches'");
    for (size_t k = 0; k < it->size(); ++k)
      panel.notches.push_back(
          readMarkingPoint((*it)[k], panel, f, "'notches' point " + std::to_string(k), unitsInMeter));
  }
  if (const auto it = pj.find("internal_lines"); it != pj.end()) {
    f.expectArray(*it, where, "'internal_lines'");
    for (size_t k = 0; k < it->size(); ++k) {
      const std::string line = "'internal_lines' line " + std::to_string(k);
      const Json& lj = (*it)[k];
      f.expectArray(lj, where, line);
      if (lj.size() < 2)
        f.fail(where, line + " must be a polyline of at least 2 points [[x, y], ...], got " + detail::describeType(lj));
      std::vector<Eigen::Vector2d> points;
      for (size_t j = 0; j < lj.size(); ++j)
        points.push_back(readMarkingPoint(lj[j], panel, f, line + " point " + std::to_string(j), unitsInMeter));
      panel.internalLines.push_back(std::move(points));
    }
  }
}

Panel readPanel(const std::string& name, const Json& pj, const JsonFields& f, const FileProperties& props,
                Diagnostics& diagnostics) {
  Panel panel;
  panel.name = name;
  const std::string where = "panel '" + name + "'";
  if (name.empty()) f.fail("", "a panel has an empty name");
  f.expectObject(pj, where, "the panel");

  const Json& vertices = f.member(pj, "vertices", where);
  f.expectArray(vertices, where, "'vertices'");
  if (vertices.empty()) f.fail(where, "empty panel: 'vertices' is empty");
  for (size_t i = 0; i < vertices.size(); ++i)
    panel.vertices.push_back(f.readVec2(vertices[i], where, "vertex " + std::to_string(i)));
  if (panel.vertices.size() < 2)
    f.fail(where, "empty panel: needs at least 2 vertices, got " + std::to_string(panel.vertices.size()));

  readEdges(panel, f.member(pj, "edges", where), f, props, diagnostics);
  panel.translation = f.readVec3(f.member(pj, "translation", where), where, "'translation'");
  panel.rotationDeg = f.readVec3(f.member(pj, "rotation", where), where, "'rotation'");
  if (const auto label = pj.find("label"); label != pj.end()) panel.label = f.readString(*label, where, "'label'");
  readMarkings(panel, pj, f, props.unitsInMeter);
  detail::validatePanelPlacement(panel, props.unitsInMeter, f);
  detail::validatePanelOutline(panel, props.unitsInMeter, f);
  return panel;
}

// Panels in panel_order when the file has one (panels it leaves out follow, in file order, with a warning).
std::vector<Panel> orderPanels(std::vector<Panel> panels, const Json& patternJson, const JsonFields& f,
                               Diagnostics& diagnostics) {
  const auto it = patternJson.find("panel_order");
  if (it == patternJson.end()) return panels;
  f.expectArray(*it, "pattern", "'panel_order'");
  std::vector<Panel> ordered;
  std::vector<bool> taken(panels.size(), false);
  for (size_t k = 0; k < it->size(); ++k) {
    const std::string name = f.readString((*it)[k], "panel_order", "entry " + std::to_string(k));
    size_t i = 0;
    while (i < panels.size() && panels[i].name != name) ++i;
    if (i == panels.size()) f.fail("panel_order", "names panel '" + name + "', which is not in 'panels'");
    if (taken[i]) f.fail("panel_order", "names panel '" + name + "' twice");
    taken[i] = true;
    ordered.push_back(std::move(panels[i]));
  }
  for (size_t i = 0; i < panels.size(); ++i) {
    if (taken[i]) continue;
    diagnostics.warn(f.source() + ": panel_order does not list panel '" + panels[i].name + "'; appended");
    ordered.push_back(std::move(panels[i]));
  }
  return ordered;
}

StitchSide readStitchSide(const Json& sj, const Pattern& pattern, const JsonFields& f, const std::string& where) {
  f.expectObject(sj, where, "each stitch side");
  const std::string name = f.readString(f.member(sj, "panel", where), where, "'panel'");
  const int edge = f.readIndex(f.member(sj, "edge", where), where, "'edge'");
  StitchSide side;
  side.panel = pattern.panelIndex(name);
  if (side.panel < 0) f.fail(where, "panel '" + name + "' does not exist");
  const int ne = int(pattern.panels[side.panel].edges.size());
  if (edge >= ne)
    f.fail(where,
           "panel '" + name + "' has no edge " + std::to_string(edge) + " (it has " + std::to_string(ne) + " edges)");
  side.edge = edge;
  return side;
}

void readStitches(Pattern& pattern, const Json& patternJson, const JsonFields& f) {
  const auto it = patternJson.find("stitches");
  if (it == patternJson.end()) return;
  f.expectArray(*it, "pattern", "'stitches'");
  std::map<std::pair<int, int>, size_t> stitchedBy;
  for (size_t k = 0; k < it->size(); ++k) {
    const std::string where = "stitch " + std::to_string(k);
    const Json& sj = (*it)[k];
    if (!sj.is_array() || sj.size() < 2 || sj.size() > 3)
      f.fail(where, "must be an array [{panel, edge}, {panel, edge}] with an optional \"right_wrong\", got " +
                        detail::describeType(sj));
    Stitch stitch;
    stitch.a = readStitchSide(sj[0], pattern, f, where);
    stitch.b = readStitchSide(sj[1], pattern, f, where);
    if (sj.size() == 3) {
      const std::string flag = f.readString(sj[2], where, "the third element");
      if (flag != "right_wrong") f.fail(where, "unknown stitch flag '" + flag + "' (expected \"right_wrong\")");
      stitch.rightWrong = true;
    }
    for (const StitchSide& side : {stitch.a, stitch.b}) {
      const auto [prev, inserted] = stitchedBy.emplace(std::make_pair(side.panel, side.edge), k);
      if (inserted) continue;
      const std::string edgeName = "panel '" + pattern.panels[side.panel].name + "' edge " + std::to_string(side.edge);
      if (prev->second == k) f.fail(where, edgeName + " is stitched to itself");
      f.fail(where, edgeName + " is stitched twice (already in stitch " + std::to_string(prev->second) + ")");
    }
    pattern.stitches.push_back(stitch);
  }
}

}  // namespace

Pattern parsePattern(const std::string& jsonText, const std::string& source, Diagnostics* diagnostics) {
  Diagnostics localDiagnostics;
  Diagnostics& diag = diagnostics ? *diagnostics : localDiagnostics;
  const JsonFields f(source);

  Json root;
  try {
    root = Json::parse(jsonText);
  } catch (const Json::exception& e) {
    f.fail("", "invalid JSON: " + json::describeParseFailure(jsonText, e));
  }
  refuseDuplicateKeys(jsonText, f);
  f.expectObject(root, "", "the top level");
  const Json& patternJson = f.member(root, "pattern", "");
  f.expectObject(patternJson, "", "'pattern'");
  const FileProperties props = readProperties(root, f, diag);

  Pattern pattern;
  pattern.source = source;
  pattern.unitsInMeter = props.unitsInMeter;
  const Json& panelsJson = f.member(patternJson, "panels", "pattern");
  f.expectObject(panelsJson, "pattern", "'panels'");
  if (panelsJson.empty()) f.fail("pattern", "no panels: 'panels' is empty");
  std::vector<Panel> panels;
  for (const auto& [name, pj] : panelsJson.items()) panels.push_back(readPanel(name, pj, f, props, diag));
  pattern.panels = orderPanels(std::move(panels), patternJson, f, diag);
  readStitches(pattern, patternJson, f);
  detail::checkStitchLengths(pattern, diag);
  return pattern;
}

Pattern loadPattern(const std::filesystem::path& file, Diagnostics* diagnostics) {
  if (isDxfFile(file)) return readDxfAamaPattern(file, diagnostics);
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open the pattern file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(file.string() + ": cannot read the pattern file");
  return parsePattern(text.str(), file.string(), diagnostics);
}

}  // namespace drape
