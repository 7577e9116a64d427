// Pattern edits of the pattern view: pure functions from one Pattern to the next.
#include "drape/pattern/pattern_edit.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "drape/core/input_error.h"
#include "drape/pattern/edge_curve.h"
#include "drape/pattern/pattern_loader.h"
#include "drape/pattern/pattern_writer.h"
#include "pattern/curve_geometry.h"

namespace drape {
namespace {

std::string where(const Pattern& pattern, int panel) {
  return pattern.source + ": panel '" + pattern.panels[static_cast<size_t>(panel)].name + "'";
}

void checkPanel(const Pattern& pattern, int panel) {
  if (panel < 0 || panel >= static_cast<int>(pattern.panels.size()))
    throw InputError(pattern.source + ": no panel " + std::to_string(panel) + " (the pattern has " +
                     std::to_string(pattern.panels.size()) + ")");
}

void checkIndex(const Pattern& pattern, int panel, int index, size_t count, const char* what) {
  checkPanel(pattern, panel);
  if (index < 0 || index >= static_cast<int>(count))
    throw InputError(where(pattern, panel) + ": no " + what + " " + std::to_string(index) + " (it has " +
                     std::to_string(count) + ")");
}

void refuseSewn(const Pattern& pattern, int panel, int edge, const std::string& action) {
  const int seam = seamOfEdge(pattern, panel, edge);
  if (seam >= 0)
    throw InputError(where(pattern, panel) + " edge " + std::to_string(edge) + " is sewn (seam " +
                     std::to_string(seam) + "): unpick the seam before " + action);
}

// The control points of a Bezier edge in absolute coordinates: start, controls..., end.
std::vector<Eigen::Vector2d> absolutePolygon(const Panel& p, const PanelEdge& e) {
  const Eigen::Vector2d s = p.vertices[static_cast<size_t>(e.start)], t = p.vertices[static_cast<size_t>(e.end)];
  std::vector<Eigen::Vector2d> out{s};
  for (const Eigen::Vector2d& c : e.curve.controls) out.push_back(detail::relativeToAbsolute(s, t, c));
  out.push_back(t);
  return out;
}

// de Casteljau: the two halves of a Bezier control polygon split at t.
std::pair<std::vector<Eigen::Vector2d>, std::vector<Eigen::Vector2d>> splitBezier(std::vector<Eigen::Vector2d> q,
                                                                                  double t) {
  std::vector<Eigen::Vector2d> left{q.front()}, right{q.back()};
  while (q.size() > 1) {
    for (size_t i = 0; i + 1 < q.size(); ++i) q[i] = (1.0 - t) * q[i] + t * q[i + 1];
    q.pop_back();
    left.push_back(q.front());
    right.push_back(q.back());
  }
  return {left, {right.rbegin(), right.rend()}};
}

EdgeCurve bezierCurve(CurveType type, const std::vector<Eigen::Vector2d>& polygon) {
  EdgeCurve c;
  c.type = type;
  for (size_t i = 1; i + 1 < polygon.size(); ++i)
    c.controls.push_back(detail::absoluteToRelative(polygon.front(), polygon.back(), polygon[i]));
  return c;
}

// Renumbers every stitch side of `panel` whose edge index is at least `from` by `delta`.
void shiftStitchEdges(Pattern& pattern, int panel, int from, int delta) {
  for (Stitch& s : pattern.stitches)
    for (StitchSide* side : {&s.a, &s.b})
      if (side->panel == panel && side->edge >= from) side->edge += delta;
}

}  // namespace

int seamOfEdge(const Pattern& pattern, int panel, int edge) {
  for (size_t s = 0; s < pattern.stitches.size(); ++s) {
    const Stitch& st = pattern.stitches[s];
    if ((st.a.panel == panel && st.a.edge == edge) || (st.b.panel == panel && st.b.edge == edge))
      return static_cast<int>(s);
  }
  return -1;
}

Pattern moveVertex(const Pattern& pattern, int panel, int vertex, const Eigen::Vector2d& to) {
  checkIndex(pattern, panel, vertex, pattern.panels[static_cast<size_t>(std::max(panel, 0))].vertices.size(), "vertex");
  if (!to.allFinite()) throw InputError(where(pattern, panel) + " vertex " + std::to_string(vertex) + ": not finite");
  Pattern out = pattern;
  out.panels[static_cast<size_t>(panel)].vertices[static_cast<size_t>(vertex)] = to;
  return out;
}

Pattern moveControlPoint(const Pattern& pattern, int panel, int edge, int control, const Eigen::Vector2d& to) {
  checkIndex(pattern, panel, edge, pattern.panels[static_cast<size_t>(std::max(panel, 0))].edges.size(), "edge");
  const Panel& p = pattern.panels[static_cast<size_t>(panel)];
  const PanelEdge& e = p.edges[static_cast<size_t>(edge)];
  if (e.curve.type != CurveType::Quadratic && e.curve.type != CurveType::Cubic)
    throw InputError(where(pattern, panel) + " edge " + std::to_string(edge) + " has no control points");
  if (control < 0 || control >= static_cast<int>(e.curve.controls.size()))
    throw InputError(where(pattern, panel) + " edge " + std::to_string(edge) + ": no control point " +
                     std::to_string(control));
  if (!to.allFinite()) throw InputError(where(pattern, panel) + " edge " + std::to_string(edge) + ": not finite");
  Pattern out = pattern;
  out.panels[static_cast<size_t>(panel)].edges[static_cast<size_t>(edge)].curve.controls[static_cast<size_t>(control)] =
      detail::absoluteToRelative(p.vertices[static_cast<size_t>(e.start)], p.vertices[static_cast<size_t>(e.end)], to);
  return out;
}

Pattern insertVertex(const Pattern& pattern, int panel, int edge, double t) {
  checkIndex(pattern, panel, edge, pattern.panels[static_cast<size_t>(std::max(panel, 0))].edges.size(), "edge");
  if (!(t > 0.0 && t < 1.0))
    throw InputError(where(pattern, panel) + " edge " + std::to_string(edge) +
                     ": split point must lie inside the edge");
  refuseSewn(pattern, panel, edge, "splitting the edge");
  Pattern out = pattern;
  Panel& p = out.panels[static_cast<size_t>(panel)];
  const PanelEdge old = p.edges[static_cast<size_t>(edge)];
  const Eigen::Vector2d at = evaluateEdge(p, edge, t);
  // The new vertex is appended to the panel's vertices, so no vertex index changes; the edges after the split shift.
  const int nv = static_cast<int>(p.vertices.size());
  p.vertices.push_back(at);
  PanelEdge first = old, second = old;
  first.end = nv;
  second.start = nv;
  second.label.clear();
  if (old.curve.type == CurveType::Quadratic || old.curve.type == CurveType::Cubic) {
    const auto [left, right] = splitBezier(absolutePolygon(pattern.panels[static_cast<size_t>(panel)], old), t);
    first.curve = bezierCurve(old.curve.type, left);
    second.curve = bezierCurve(old.curve.type, right);
  } else if (old.curve.type == CurveType::Circle) {
    const Panel& before = pattern.panels[static_cast<size_t>(panel)];
    const detail::CurveGeometry arc(before.vertices[static_cast<size_t>(old.start)],
                                    before.vertices[static_cast<size_t>(old.end)], old.curve);
    first.curve.radius = second.curve.radius = arc.circleRadius();
    first.curve.largeArc = std::abs(t * arc.circleSweep()) > std::numbers::pi;
    second.curve.largeArc = std::abs((1.0 - t) * arc.circleSweep()) > std::numbers::pi;
  }
  p.edges[static_cast<size_t>(edge)] = first;
  p.edges.insert(p.edges.begin() + edge + 1, second);
  shiftStitchEdges(out, panel, edge + 1, 1);
  return out;
}

Pattern deleteVertex(const Pattern& pattern, int panel, int vertex) {
  checkIndex(pattern, panel, vertex, pattern.panels[static_cast<size_t>(std::max(panel, 0))].vertices.size(), "vertex");
  const Panel& p = pattern.panels[static_cast<size_t>(panel)];
  if (p.vertices.size() <= 3) throw InputError(where(pattern, panel) + ": a panel keeps at least three vertices");
  int in = -1, outgoing = -1;
  for (size_t e = 0; e < p.edges.size(); ++e) {
    if (p.edges[e].end == vertex) in = static_cast<int>(e);
    if (p.edges[e].start == vertex) outgoing = static_cast<int>(e);
  }
  if (in < 0 || outgoing < 0)
    throw InputError(where(pattern, panel) + " vertex " + std::to_string(vertex) + " is not on the outline");
  refuseSewn(pattern, panel, in, "deleting vertex " + std::to_string(vertex));
  refuseSewn(pattern, panel, outgoing, "deleting vertex " + std::to_string(vertex));
  Pattern out = pattern;
  Panel& q = out.panels[static_cast<size_t>(panel)];
  PanelEdge joined;
  joined.start = q.edges[static_cast<size_t>(in)].start;
  joined.end = q.edges[static_cast<size_t>(outgoing)].end;
  joined.label = q.edges[static_cast<size_t>(in)].label;
  q.edges[static_cast<size_t>(in)] = joined;
  q.edges.erase(q.edges.begin() + outgoing);
  shiftStitchEdges(out, panel, outgoing + 1, -1);
  q.vertices.erase(q.vertices.begin() + vertex);
  for (PanelEdge& e : q.edges) {
    if (e.start > vertex) --e.start;
    if (e.end > vertex) --e.end;
  }
  return out;
}

Pattern sewEdges(const Pattern& pattern, const StitchSide& a, const StitchSide& b) {
  for (const StitchSide& s : {a, b})
    checkIndex(pattern, s.panel, s.edge, pattern.panels[static_cast<size_t>(std::max(s.panel, 0))].edges.size(),
               "edge");
  if (a.panel == b.panel && a.edge == b.edge)
    throw InputError(where(pattern, a.panel) + " edge " + std::to_string(a.edge) + " cannot be sewn to itself");
  for (const StitchSide& s : {a, b}) refuseSewn(pattern, s.panel, s.edge, "sewing it again");
  Pattern out = pattern;
  Stitch st;
  st.a = a;
  st.b = b;
  out.stitches.push_back(st);
  return out;
}

Pattern unpickSeam(const Pattern& pattern, int stitch) {
  if (stitch < 0 || stitch >= static_cast<int>(pattern.stitches.size()))
    throw InputError(pattern.source + ": no seam " + std::to_string(stitch) + " (the pattern has " +
                     std::to_string(pattern.stitches.size()) + ")");
  Pattern out = pattern;
  out.stitches.erase(out.stitches.begin() + stitch);
  return out;
}

Pattern validatedPattern(const Pattern& pattern, Diagnostics* diagnostics) {
  std::string text;
  try {
    text = patternToJson(pattern);
  } catch (const std::invalid_argument& e) {  // what JSON cannot hold (a repeated panel name, a bad index)
    throw InputError(pattern.source + ": " + e.what());
  }
  return parsePattern(text, pattern.source, diagnostics);
}

}  // namespace drape
