// One DXF-AAMA piece block -> Panel: the layer-1 boundary chained into one loop, checked (distinct points,
// simple, with area, within the panel size limits) and made counter-clockwise; then the markings.
#include "pattern/dxf_aama_piece.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "drape/core/input_error.h"
#include "pattern/curve_geometry.h"
#include "pattern/pattern_validation.h"

namespace drape::detail {
namespace {

// Points closer than this fraction of the boundary's extent are one point (closing points, joints of parts).
constexpr double kCoincident = 1e-6;
// Segments per arc (polyline bulge) for the self-intersection test and for internal lines.
constexpr int kArcSegments = 32;

std::string formatNumber(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

std::string formatPoint(const Eigen::Vector2d& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.6g, %.6g)", p.x(), p.y());
  return buffer;
}

bool isNotchLayer(const std::string& layer) {
  return layer == "4" || (layer.size() == 2 && layer[0] == '8' && layer[1] >= '0' && layer[1] <= '5');
}

// A polyline bulge (tan of a quarter of the arc's sweep, > 0 counter-clockwise) as a circular EdgeCurve.
EdgeCurve curveFromBulge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double bulge) {
  EdgeCurve curve;
  const double chord = (b - a).norm();
  if (!(std::abs(bulge) > 1e-9) || !std::isfinite(bulge) || chord == 0.0) return curve;
  curve.type = CurveType::Circle;
  curve.radius = chord * (1.0 + bulge * bulge) / (4.0 * std::abs(bulge));
  curve.largeArc = std::abs(bulge) > 1.0;
  curve.right = bulge > 0.0;  // counter-clockwise about the centre
  return curve;
}

// An open chain: bulges[i] belongs to the segment points[i] -> points[i + 1] (the last one is unused).
// As a closed loop the last bulge belongs to the closing segment.
struct Chain {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> bulges;
};

Chain chainOf(const DxfPolyline& p) {
  Chain c{p.points, p.bulges};
  c.bulges.resize(c.points.size(), 0.0);
  return c;
}

// Reverses an open chain (closed = false) or a closed loop; each arc is then run the other way.
Chain reversed(const Chain& c, bool closed) {
  const size_t n = c.points.size();
  Chain r{{c.points.rbegin(), c.points.rend()}, std::vector<double>(n, 0.0)};
  for (size_t j = 0; j < n; ++j) {
    if (!closed && j + 1 == n) break;
    r.bulges[j] = -c.bulges[(2 * n - 2 - j) % n];
  }
  return r;
}

class PieceBuilder {
 public:
  PieceBuilder(const DxfBlock& block, const std::string& name, const std::string& source, Diagnostics& diagnostics)
      : m_block(block), m_where(source + ": piece '" + name + "'"), m_diagnostics(diagnostics) {}

  [[noreturn]] void fail(const std::string& problem) const { throw InputError(m_where + ": " + problem); }
  void warn(const std::string& problem) const { m_diagnostics.warn(m_where + ": " + problem); }

  // The layer-1 parts joined into one closed loop, coincident neighbours merged.
  Chain boundary() const {
    std::vector<Chain> parts;
    int closedParts = 0;
    Eigen::AlignedBox2d box;
    for (const DxfPolyline& p : m_block.polylines) {
      if (p.layer != "1" || p.points.size() < 2) continue;  // a POINT on layer 1 is not part of the outline
      parts.push_back(chainOf(p));
      closedParts += p.closed ? 1 : 0;
      for (const auto& q : p.points) box.extend(q);
    }
    if (parts.empty()) fail("no boundary (no POLYLINE, LWPOLYLINE or LINE on layer 1" + skippedOnLayer1() + ")");
    const double tolerance = kCoincident * box.diagonal().norm();
    auto same = [tolerance](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return (a - b).norm() <= tolerance; };
    if (closedParts > 0 && parts.size() > 1)
      fail("boundary is not one closed loop: layer 1 holds " + std::to_string(parts.size()) + " parts, " +
           std::to_string(closedParts) + " of them closed");

    Chain loop = parts[0];
    std::vector<bool> used(parts.size(), false);
    used[0] = true;
    for (bool extended = true; extended;) {
      extended = false;
      for (size_t k = 0; k < parts.size() && !extended; ++k) {
        if (used[k]) continue;
        Chain next = parts[k];
        if (same(next.points.back(), loop.points.back())) next = reversed(next, false);
        if (!same(next.points.front(), loop.points.back())) continue;
        loop.bulges.back() = next.bulges.front();
        loop.points.insert(loop.points.end(), next.points.begin() + 1, next.points.end());
        loop.bulges.insert(loop.bulges.end(), next.bulges.begin() + 1, next.bulges.end());
        used[k] = extended = true;
      }
    }
    const auto chained = std::count(used.begin(), used.end(), true);
    if (chained < long(parts.size()))
      fail("boundary is not one closed loop: of its " + std::to_string(parts.size()) + " parts on layer 1, " +
           std::to_string(chained) + " chain from " + formatPoint(loop.points.front()) + " to " +
           formatPoint(loop.points.back()) + " and the others do not join them");
    const bool closes = loop.points.size() > 1 && same(loop.points.front(), loop.points.back());
    if (closes) {
      loop.points.pop_back();
      loop.bulges.pop_back();
    } else if (parts.size() > 1) {
      fail("boundary is not one closed loop: its parts on layer 1 chain from " + formatPoint(loop.points.front()) +
           " to " + formatPoint(loop.points.back()));
    } else if (closedParts == 0 && loop.points.size() > 2) {
      warn("the boundary polyline is open; closed by a straight edge from " + formatPoint(loop.points.back()) + " to " +
           formatPoint(loop.points.front()));
    }

    Chain merged;  // consecutive coincident points merged; the segment leaving the last of them is kept
    for (size_t i = 0; i < loop.points.size(); ++i) {
      if (!merged.points.empty() && same(loop.points[i], merged.points.back())) {
        merged.bulges.back() = loop.bulges[i];
        continue;
      }
      merged.points.push_back(loop.points[i]);
      merged.bulges.push_back(loop.bulges[i]);
    }
    while (merged.points.size() > 1 && same(merged.points.back(), merged.points.front())) {
      merged.points.pop_back();
      merged.bulges.pop_back();
    }
    return merged;
  }

  std::string skippedOnLayer1() const {
    for (const std::string& s : m_block.skipped)
      if (s.size() > 11 && s.compare(s.size() - 11, 11, " on layer 1") == 0) return "; " + s + " is not read";
    return "";
  }

  // Warnings for what is in the block but not read.
  void warnUnread() const {
    std::map<std::string, int> counts;
    for (const std::string& s : m_block.skipped) ++counts[s];
    std::string list;
    for (const auto& [what, n] : counts)
      list += (list.empty() ? "" : ", ") + what + (n > 1 ? " (x" + std::to_string(n) + ")" : "");
    if (!list.empty()) warn("not read: " + list);
    auto onLayer = [this](const char* layer) {
      for (const auto& p : m_block.polylines)
        if (p.layer == layer) return true;
      return false;
    };
    if (onLayer("6")) warn("the mirror line (layer 6) is ignored: the piece is read as drawn, not unfolded");
    if (onLayer("11")) warn("internal cutouts (layer 11) are ignored");
  }

 private:
  const DxfBlock& m_block;
  std::string m_where;
  Diagnostics& m_diagnostics;
};

Panel panelFromLoop(const Chain& loop, const std::string& name) {
  Panel panel;
  panel.name = name;
  panel.vertices = loop.points;
  const int n = int(loop.points.size());
  for (int i = 0; i < n; ++i) {
    PanelEdge edge;
    edge.start = i;
    edge.end = (i + 1) % n;
    edge.curve = curveFromBulge(loop.points[i], loop.points[(i + 1) % n], loop.bulges[i]);
    panel.edges.push_back(edge);
  }
  return panel;
}

// The points of an open polyline, arcs sampled; a closed one ends where it starts.
std::vector<Eigen::Vector2d> polylinePoints(const DxfPolyline& p) {
  std::vector<Eigen::Vector2d> points;
  const size_t n = p.points.size();
  const size_t segments = p.closed ? n : n - 1;
  for (size_t i = 0; i < segments; ++i) {
    const Eigen::Vector2d& a = p.points[i];
    const Eigen::Vector2d& b = p.points[(i + 1) % n];
    const EdgeCurve curve = curveFromBulge(a, b, i < p.bulges.size() ? p.bulges[i] : 0.0);
    const int k = curve.type == CurveType::Straight ? 1 : kArcSegments;
    const CurveGeometry geometry(a, b, curve);
    for (int j = 0; j < k; ++j) points.push_back(geometry.point(double(j) / k));
  }
  points.push_back(p.closed ? p.points.front() : p.points.back());
  return points;
}

double distanceToOutline(const Eigen::Vector2d& x, const std::vector<Eigen::Vector2d>& outline) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < outline.size(); ++i) {
    const Eigen::Vector2d& a = outline[i];
    const Eigen::Vector2d d = outline[(i + 1) % outline.size()] - a;
    const double t = d.squaredNorm() > 0.0 ? std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * d - x).norm());
  }
  return best;
}

}  // namespace

Panel buildAamaPanel(const DxfBlock& block, const std::string& name, double unitsInMeter, const std::string& source,
                     Diagnostics& diagnostics) {
  const PieceBuilder builder(block, name, source, diagnostics);
  if (!block.badNumber.empty()) builder.fail(block.badNumber);
  Chain loop = builder.boundary();
  if (loop.points.size() < 3)
    builder.fail("boundary has " + std::to_string(loop.points.size()) + " distinct point" +
                 (loop.points.size() == 1 ? "" : "s") + " (at least 3 needed)");

  Panel panel = panelFromLoop(loop, name);
  std::vector<int> edgeOfSegment;
  std::vector<Eigen::Vector2d> outline = sampledOutline(panel, kArcSegments, &edgeOfSegment);
  if (const auto contact = findSelfContact(outline))
    builder.fail("boundary crosses itself near " + formatPoint(contact->point) + " (boundary segments " +
                 std::to_string(edgeOfSegment[contact->segmentA]) + " and " +
                 std::to_string(edgeOfSegment[contact->segmentB]) + ")");
  Eigen::AlignedBox2d box;
  for (const auto& p : outline) box.extend(p);
  const double diagonal = box.diagonal().norm();
  const double area = signedArea(outline);
  if (std::abs(area) <= 1e-9 * diagonal * diagonal) builder.fail("boundary encloses no area");
  const double areaM2 = std::abs(area) / (unitsInMeter * unitsInMeter);
  if (areaM2 < kMinPanelArea)
    builder.fail("area " + formatNumber(areaM2) + " m^2 is too small to mesh (at least " + formatNumber(kMinPanelArea) +
                 " m^2 is needed; are the units right?)");
  if (diagonal / unitsInMeter > kMaxPanelExtent)
    builder.fail("boundary is " + formatNumber(diagonal / unitsInMeter) + " m across (at most " +
                 formatNumber(kMaxPanelExtent) + " m; are the units right?)");
  if (area < 0.0) {  // clockwise as drawn: the outside of the piece faces the viewer, so run it the other way
    panel = panelFromLoop(reversed(loop, true), name);
    outline = sampledOutline(panel, kArcSegments);
  }

  int grainLines = 0;
  for (const DxfPolyline& p : block.polylines) {
    if (p.points.empty()) continue;
    if (p.layer == "7" && p.points.size() >= 2 && ++grainLines == 1) {
      if ((p.points.back() - p.points.front()).norm() > kCoincident * diagonal)
        panel.grainLine = std::array<Eigen::Vector2d, 2>{p.points.front(), p.points.back()};
      else
        builder.warn("the grain line on layer 7 has no length; ignored");
    } else if (p.layer == "8" && p.points.size() >= 2) {
      panel.internalLines.push_back(polylinePoints(p));
    } else if (isNotchLayer(p.layer)) {
      const auto nearest = std::min_element(p.points.begin(), p.points.end(), [&](const auto& a, const auto& b) {
        return distanceToOutline(a, outline) < distanceToOutline(b, outline);
      });
      panel.notches.push_back(*nearest);
    }
  }
  if (grainLines > 1) builder.warn(std::to_string(grainLines) + " grain lines on layer 7; the first is used");
  // As in pattern files: markings within kMaxPanelExtent metres of the corners' box.
  Eigen::AlignedBox2d corners;
  for (const auto& v : panel.vertices) corners.extend(v);
  auto near = [&](const Eigen::Vector2d& p, const std::string& what) {
    const double away = corners.exteriorDistance(p) / unitsInMeter;
    if (!(away <= kMaxPanelExtent))
      builder.fail(what + " " + formatPoint(p) + " is " + formatNumber(away) + " m from the piece's corners (at most " +
                   formatNumber(kMaxPanelExtent) + " m)");
  };
  if (panel.grainLine)
    for (const auto& p : *panel.grainLine) near(p, "the grain line's point");
  for (const auto& n : panel.notches) near(n, "the notch");
  for (const auto& line : panel.internalLines)
    for (const auto& p : line) near(p, "an internal line's point");
  builder.warnUnread();
  return panel;
}

}  // namespace drape::detail
