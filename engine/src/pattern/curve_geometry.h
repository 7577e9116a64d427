#pragma once
// Private: the absolute geometry of one panel edge (straight segment, quadratic or cubic Bezier, circular arc)
// built from its endpoints and EdgeCurve, with arc length by adaptive Gauss-Legendre quadrature and the
// inverse map arc length -> curve parameter. Everything in the panel's 2D frame, file units.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "drape/pattern/pattern.h"

namespace drape::detail {

// Relative control point (x along start->end, y along the left normal, both as fractions of the chord)
// to absolute panel coordinates: start + x * (end - start) + y * perpLeft(end - start).
Eigen::Vector2d relativeToAbsolute(const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                                   const Eigen::Vector2d& relative);

// The inverse of relativeToAbsolute; start and end must differ.
Eigen::Vector2d absoluteToRelative(const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                                   const Eigen::Vector2d& absolute);

class CurveGeometry {
 public:
  // start/end: the edge's endpoint positions (file units). A circle whose radius is below half the chord is
  // drawn with radius = half the chord (as SVG does); the loader rejects radii clearly too small.
  CurveGeometry(const Eigen::Vector2d& start, const Eigen::Vector2d& end, const EdgeCurve& curve);

  // Point and derivative d/dt at curve parameter t in [0, 1].
  Eigen::Vector2d point(double t) const;
  Eigen::Vector2d derivative(double t) const;

  // Total arc length, file units.
  double length() const { return table().back(); }

  // Curve parameter t at which the arc length from the start equals s (clamped to [0, length()]).
  double parameterAtLength(double s) const;

  // segments + 1 points spaced evenly by arc length; the first and last are exactly start and end.
  std::vector<Eigen::Vector2d> sampleByArcLength(int segments) const;

  // Circle only: centre and signed sweep angle (radians, > 0 counter-clockwise).
  const Eigen::Vector2d& circleCenter() const { return m_center; }
  double circleSweep() const { return m_sweep; }
  double circleRadius() const { return m_radius; }

 private:
  double integrateSpeed(double t0, double t1) const;
  // The arc-length table, built on first use (evaluation alone never needs it).
  const std::vector<double>& table() const;

  CurveType m_type;
  std::array<Eigen::Vector2d, 4> m_points;  // Bezier control polygon (Straight: 2, Quadratic: 3, Cubic: 4 used)
  Eigen::Vector2d m_center = Eigen::Vector2d::Zero();
  double m_radius = 0.0;
  double m_startAngle = 0.0;
  double m_sweep = 0.0;
  mutable std::vector<double> m_cumulative;  // arc length at knots t = i / (size - 1); empty until table()
};

}  // namespace drape::detail
