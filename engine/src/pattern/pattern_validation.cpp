#include "pattern/pattern_validation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "drape/core/input_error.h"
#include "drape/pattern/edge_curve.h"
#include "pattern/curve_geometry.h"

namespace drape::detail {
namespace {

// Segments per curved edge for the outline checks: fine enough to see a cubic's loop or a near miss.
constexpr int kCheckSegmentsPerCurve = 64;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

std::string formatNumber(double x, int precision = 4) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", precision, x);
  return buffer;
}

// Contact of segments [p, q] and [r, s]; eps is the orientation tolerance (squared length units).
std::optional<Eigen::Vector2d> segmentContact(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                                              const Eigen::Vector2d& r, const Eigen::Vector2d& s, double eps) {
  const double o1 = cross(q - p, r - p), o2 = cross(q - p, s - p);
  const double o3 = cross(s - r, p - r), o4 = cross(s - r, q - r);
  auto sign = [eps](double o) { return o > eps ? 1 : (o < -eps ? -1 : 0); };
  const int s1 = sign(o1), s2 = sign(o2), s3 = sign(o3), s4 = sign(o4);
  if (s1 * s2 < 0 && s3 * s4 < 0) {
    const double t = o3 / (o3 - o4);
    return p + t * (q - p);
  }
  // Touching or collinear: some endpoint lies on the other segment.
  auto onSegment = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& x) {
    return x.x() >= std::min(a.x(), b.x()) && x.x() <= std::max(a.x(), b.x()) && x.y() >= std::min(a.y(), b.y()) &&
           x.y() <= std::max(a.y(), b.y());
  };
  if (s1 == 0 && onSegment(p, q, r)) return r;
  if (s2 == 0 && onSegment(p, q, s)) return s;
  if (s3 == 0 && onSegment(r, s, p)) return p;
  if (s4 == 0 && onSegment(r, s, q)) return q;
  return std::nullopt;
}

}  // namespace

double signedArea(const std::vector<Eigen::Vector2d>& outline) {
  double twice = 0.0;
  for (size_t i = 0; i < outline.size(); ++i) twice += cross(outline[i], outline[(i + 1) % outline.size()]);
  return 0.5 * twice;
}

std::optional<OutlineContact> findSelfContact(const std::vector<Eigen::Vector2d>& outline) {
  const int n = int(outline.size());
  if (n < 3) return std::nullopt;
  Eigen::AlignedBox2d box;
  for (const auto& p : outline) box.extend(p);
  const double scale = std::max(box.diagonal().norm(), 1e-300);
  const double eps = 1e-12 * scale * scale;

  // Adjacent segments may only share their common point: a fold back along the same line is a contact.
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d& a = outline[k];
    const Eigen::Vector2d& b = outline[(k + 1) % n];
    const Eigen::Vector2d& c = outline[(k + 2) % n];
    if (std::abs(cross(b - a, c - b)) <= eps && (b - a).dot(c - b) < 0.0) return OutlineContact{k, (k + 1) % n, b};
  }

  // Sweep along x: candidate pairs are those whose x-ranges overlap.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto minX = [&](int k) { return std::min(outline[k].x(), outline[(k + 1) % n].x()); };
  auto maxX = [&](int k) { return std::max(outline[k].x(), outline[(k + 1) % n].x()); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return minX(a) < minX(b); });
  for (int i = 0; i < n; ++i) {
    const int a = order[i];
    const Eigen::Vector2d& p = outline[a];
    const Eigen::Vector2d& q = outline[(a + 1) % n];
    for (int j = i + 1; j < n && minX(order[j]) <= maxX(a); ++j) {
      const int b = order[j];
      if (b == (a + 1) % n || a == (b + 1) % n) continue;  // adjacent: share a point by construction
      const Eigen::Vector2d& r = outline[b];
      const Eigen::Vector2d& s = outline[(b + 1) % n];
      if (std::max(r.y(), s.y()) < std::min(p.y(), q.y()) || std::min(r.y(), s.y()) > std::max(p.y(), q.y())) continue;
      if (const auto hit = segmentContact(p, q, r, s, eps)) return OutlineContact{std::min(a, b), std::max(a, b), *hit};
    }
  }
  return std::nullopt;
}

std::vector<Eigen::Vector2d> sampledOutline(const Panel& panel, int segmentsPerCurve, std::vector<int>* edgeOfSegment) {
  std::vector<Eigen::Vector2d> outline;
  for (int e = 0; e < int(panel.edges.size()); ++e) {
    const PanelEdge& edge = panel.edges[e];
    const CurveGeometry geometry(panel.vertices[edge.start], panel.vertices[edge.end], edge.curve);
    const int segments = edge.curve.type == CurveType::Straight ? 1 : segmentsPerCurve;
    for (int k = 0; k < segments; ++k) {
      outline.push_back(geometry.point(double(k) / segments));
      if (edgeOfSegment) edgeOfSegment->push_back(e);
    }
  }
  return outline;
}

void validatePanelOutline(const Panel& panel, double unitsInMeter, const JsonFields& fields) {
  std::vector<int> edgeOfSegment;
  const std::vector<Eigen::Vector2d> outline = sampledOutline(panel, kCheckSegmentsPerCurve, &edgeOfSegment);
  const std::string where = "panel '" + panel.name + "'";
  if (const auto contact = findSelfContact(outline)) {
    const int ea = edgeOfSegment[contact->segmentA], eb = edgeOfSegment[contact->segmentB];
    const std::string near =
        " near (" + formatNumber(contact->point.x()) + ", " + formatNumber(contact->point.y()) + ")";
    if (ea == eb)
      fields.fail(where + " edge " + std::to_string(ea), "self-intersecting outline: the edge crosses itself" + near);
    fields.fail(where + " edge " + std::to_string(ea),
                "self-intersecting outline: crosses edge " + std::to_string(eb) + near);
  }
  Eigen::AlignedBox2d box;
  for (const auto& p : outline) box.extend(p);
  const double diagonal = box.diagonal().norm();
  const double area = std::abs(signedArea(outline));
  if (area <= 1e-9 * diagonal * diagonal) fields.fail(where, "outline encloses no area");

  // Absolute size, metres: the mesher and the cloth model need triangles far above rounding, and a panel
  // larger than a room is a unit mistake.
  const double across = diagonal / unitsInMeter;
  const double areaM2 = area / (unitsInMeter * unitsInMeter);
  if (areaM2 < kMinPanelArea)
    fields.fail(where, "area " + formatNumber(areaM2) + " m^2 is too small to mesh (its outline is " +
                           formatNumber(across) + " m across; at least " + formatNumber(kMinPanelArea) +
                           " m^2 is needed)");
  if (across > kMaxPanelExtent)
    fields.fail(where,
                "outline is " + formatNumber(across) + " m across (at most " + formatNumber(kMaxPanelExtent) + " m)");
}

void validatePanelPlacement(const Panel& panel, double unitsInMeter, const JsonFields& fields) {
  const std::string where = "panel '" + panel.name + "'";
  const double distance = panel.translation.stableNorm() / unitsInMeter;  // no overflow at 1e308
  if (!(distance <= kMaxPanelTranslation))
    fields.fail(where, "'translation' (" + formatNumber(panel.translation.x()) + ", " +
                           formatNumber(panel.translation.y()) + ", " + formatNumber(panel.translation.z()) + ") is " +
                           formatNumber(distance) + " m from the origin (at most " +
                           formatNumber(kMaxPanelTranslation) + " m)");
  for (int k = 0; k < 3; ++k)
    if (!(std::abs(panel.rotationDeg[k]) <= kMaxPanelRotationDeg))
      fields.fail(where, std::string("'rotation' ") + "xyz"[k] + " = " + formatNumber(panel.rotationDeg[k]) +
                             " degrees is out of range [-" + formatNumber(kMaxPanelRotationDeg) + ", " +
                             formatNumber(kMaxPanelRotationDeg) + "]");
}

void checkStitchLengths(const Pattern& pattern, Diagnostics& diagnostics) {
  for (size_t k = 0; k < pattern.stitches.size(); ++k) {
    const Stitch& stitch = pattern.stitches[k];
    const Panel& pa = pattern.panels[stitch.a.panel];
    const Panel& pb = pattern.panels[stitch.b.panel];
    const double la = edgeLength(pa, stitch.a.edge), lb = edgeLength(pb, stitch.b.edge);
    const double relative = std::abs(la - lb) / std::max(la, lb);
    const std::string what = pattern.source + ": stitch " + std::to_string(k) + ": panel '" + pa.name + "' edge " +
                             std::to_string(stitch.a.edge) + " (length " + formatNumber(la) + ") and panel '" +
                             pb.name + "' edge " + std::to_string(stitch.b.edge) + " (length " + formatNumber(lb) +
                             ") differ by " + formatNumber(100.0 * relative, 3) + "%";
    if (std::max(la, lb) > kMaxStitchLengthRatio * std::min(la, lb))
      throw InputError(what + ": one is more than twice the other, too different to sew");
    if (relative > 0.05) diagnostics.warn(what);
  }
}

}  // namespace drape::detail
