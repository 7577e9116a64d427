#include "pattern/curve_geometry.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace drape::detail {
namespace {

Eigen::Vector2d perpLeft(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

// 8-point Gauss-Legendre rule on [-1, 1] (nodes symmetric about 0).
constexpr std::array<double, 4> kGaussNodes = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                               0.9602898564975363};
constexpr std::array<double, 4> kGaussWeights = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                                 0.1012285362903763};

// Knots of the cumulative arc-length table: enough that each piece of a cubic is gently curved.
constexpr int kTableSegments = 32;

}  // namespace

Eigen::Vector2d relativeToAbsolute(const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                                   const Eigen::Vector2d& relative) {
  const Eigen::Vector2d chord = end - start;
  return start + relative.x() * chord + relative.y() * perpLeft(chord);
}

Eigen::Vector2d absoluteToRelative(const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                                   const Eigen::Vector2d& absolute) {
  const Eigen::Vector2d chord = end - start;
  const Eigen::Vector2d d = absolute - start;
  const double len2 = chord.squaredNorm();
  return {d.dot(chord) / len2, d.dot(perpLeft(chord)) / len2};
}

CurveGeometry::CurveGeometry(const Eigen::Vector2d& start, const Eigen::Vector2d& end, const EdgeCurve& curve)
    : m_type(curve.type) {
  m_points.fill(Eigen::Vector2d::Zero());
  switch (m_type) {
    case CurveType::Straight:
      m_points[0] = start;
      m_points[1] = end;
      break;
    case CurveType::Quadratic:
      m_points[0] = start;
      m_points[1] = relativeToAbsolute(start, end, curve.controls.at(0));
      m_points[2] = end;
      break;
    case CurveType::Cubic:
      m_points[0] = start;
      m_points[1] = relativeToAbsolute(start, end, curve.controls.at(0));
      m_points[2] = relativeToAbsolute(start, end, curve.controls.at(1));
      m_points[3] = end;
      break;
    case CurveType::Circle: {
      // SVG arc semantics: sweep flag "right" = the arc runs counter-clockwise about its centre, so the
      // centre lies left of start -> end and a small arc bulges to the right; large_arc picks the longer way.
      const Eigen::Vector2d chord = end - start;
      const double half = 0.5 * chord.norm();
      m_radius = std::max(curve.radius, half);
      const double offset = std::sqrt(std::max(0.0, m_radius * m_radius - half * half));
      const Eigen::Vector2d leftUnit =
          half > 0.0 ? Eigen::Vector2d(perpLeft(chord) / (2.0 * half)) : Eigen::Vector2d(0.0, 1.0);
      const double side = (curve.right != curve.largeArc) ? 1.0 : -1.0;
      m_center = 0.5 * (start + end) + side * offset * leftUnit;
      m_startAngle = std::atan2(start.y() - m_center.y(), start.x() - m_center.x());
      const double endAngle = std::atan2(end.y() - m_center.y(), end.x() - m_center.x());
      const double twoPi = 2.0 * std::numbers::pi;
      double sweep = std::fmod(endAngle - m_startAngle, twoPi);
      if (curve.right) {
        if (sweep <= 0.0) sweep += twoPi;
      } else {
        if (sweep >= 0.0) sweep -= twoPi;
      }
      m_sweep = sweep;
      m_points[0] = start;
      m_points[1] = end;
      break;
    }
  }
}

const std::vector<double>& CurveGeometry::table() const {
  if (m_cumulative.empty()) {
    std::vector<double> cumulative(kTableSegments + 1, 0.0);
    for (int i = 0; i < kTableSegments; ++i)
      cumulative[i + 1] = cumulative[i] + integrateSpeed(double(i) / kTableSegments, double(i + 1) / kTableSegments);
    m_cumulative = std::move(cumulative);
  }
  return m_cumulative;
}

Eigen::Vector2d CurveGeometry::point(double t) const {
  const double s = 1.0 - t;
  switch (m_type) {
    case CurveType::Straight:
      return s * m_points[0] + t * m_points[1];
    case CurveType::Quadratic:
      return s * s * m_points[0] + 2.0 * s * t * m_points[1] + t * t * m_points[2];
    case CurveType::Cubic:
      return s * s * s * m_points[0] + 3.0 * s * s * t * m_points[1] + 3.0 * s * t * t * m_points[2] +
             t * t * t * m_points[3];
    case CurveType::Circle: {
      if (t <= 0.0) return m_points[0];
      if (t >= 1.0) return m_points[1];
      const double a = m_startAngle + t * m_sweep;
      return m_center + m_radius * Eigen::Vector2d(std::cos(a), std::sin(a));
    }
  }
  return m_points[0];
}

Eigen::Vector2d CurveGeometry::derivative(double t) const {
  const double s = 1.0 - t;
  switch (m_type) {
    case CurveType::Straight:
      return m_points[1] - m_points[0];
    case CurveType::Quadratic:
      return 2.0 * s * (m_points[1] - m_points[0]) + 2.0 * t * (m_points[2] - m_points[1]);
    case CurveType::Cubic:
      return 3.0 * s * s * (m_points[1] - m_points[0]) + 6.0 * s * t * (m_points[2] - m_points[1]) +
             3.0 * t * t * (m_points[3] - m_points[2]);
    case CurveType::Circle: {
      const double a = m_startAngle + t * m_sweep;
      return m_radius * m_sweep * Eigen::Vector2d(-std::sin(a), std::cos(a));
    }
  }
  return Eigen::Vector2d::Zero();
}

double CurveGeometry::integrateSpeed(double t0, double t1) const {
  if (m_type == CurveType::Straight) return (m_points[1] - m_points[0]).norm() * (t1 - t0);
  if (m_type == CurveType::Circle) return m_radius * std::abs(m_sweep) * (t1 - t0);
  // Adaptive Gauss-Legendre: accept a piece when one 8-point rule agrees with the sum over its halves.
  auto rule = [this](double a, double b) {
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    double sum = 0.0;
    for (size_t k = 0; k < kGaussNodes.size(); ++k) {
      sum += kGaussWeights[k] *
             (derivative(mid - half * kGaussNodes[k]).norm() + derivative(mid + half * kGaussNodes[k]).norm());
    }
    return sum * half;
  };
  struct Piece {
    double a, b, whole;
    int depth;
  };
  double total = 0.0;
  std::vector<Piece> stack{{t0, t1, rule(t0, t1), 0}};
  while (!stack.empty()) {
    const Piece p = stack.back();
    stack.pop_back();
    const double m = 0.5 * (p.a + p.b);
    const double left = rule(p.a, m), right = rule(m, p.b);
    const double split = left + right;
    if (std::abs(split - p.whole) <= 1e-12 * std::max(1.0, std::abs(split)) || p.depth >= 30) {
      total += split;
    } else {
      stack.push_back({p.a, m, left, p.depth + 1});
      stack.push_back({m, p.b, right, p.depth + 1});
    }
  }
  return total;
}

double CurveGeometry::parameterAtLength(double s) const {
  const double total = length();
  if (s <= 0.0) return 0.0;
  if (s >= total) return 1.0;
  if (m_type == CurveType::Straight || m_type == CurveType::Circle) return s / total;
  const std::vector<double>& cumulative = table();
  const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), s);
  const int i = std::clamp(int(it - cumulative.begin()) - 1, 0, kTableSegments - 1);
  double lo = double(i) / kTableSegments, hi = double(i + 1) / kTableSegments;
  const double base = cumulative[i];
  // Newton on f(t) = base + L(t_i, t) - s, kept inside the bracket [lo, hi] by bisection.
  double t = lo + (hi - lo) * (s - base) / std::max(cumulative[i + 1] - base, 1e-300);
  for (int iter = 0; iter < 50; ++iter) {
    const double f = base + integrateSpeed(double(i) / kTableSegments, t) - s;
    if (std::abs(f) <= 1e-12 * std::max(1.0, total)) break;
    if (f > 0.0)
      hi = t;
    else
      lo = t;
    const double speed = derivative(t).norm();
    double next = speed > 0.0 ? t - f / speed : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    t = next;
    if (hi - lo < 1e-15) break;
  }
  return t;
}

std::vector<Eigen::Vector2d> CurveGeometry::sampleByArcLength(int segments) const {
  segments = std::max(segments, 1);
  std::vector<Eigen::Vector2d> out;
  out.reserve(segments + 1);
  out.push_back(m_points[0]);
  const double total = length();
  for (int k = 1; k < segments; ++k) out.push_back(point(parameterAtLength(total * k / segments)));
  out.push_back(m_type == CurveType::Straight || m_type == CurveType::Circle ? m_points[1] : point(1.0));
  return out;
}

}  // namespace drape::detail
