// Cubic root isolation on monotone intervals and the vertex-triangle / edge-edge time-of-impact tests.
#include "drape/collision/ccd.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include "drape/collision/distance.h"

namespace drape::collision {
namespace {

// Roots of f' in (lo, hi), increasing; at most 2.
int criticalPoints(const Cubic& f, double lo, double hi, std::array<double, 2>& out) {
  const double A = 3.0 * f.c[3];
  const double B = 2.0 * f.c[2];
  const double C = f.c[1];
  double r[2];
  int n = 0;
  if (std::abs(A) <= 1e-14 * f.scale()) {
    if (B != 0.0) r[n++] = -C / B;
  } else {
    const double disc = B * B - 4.0 * A * C;
    if (disc >= 0.0) {
      // Stable quadratic formula (no cancellation between B and the square root).
      const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
      r[n++] = q / A;
      if (q != 0.0) r[n++] = C / q;
    }
  }
  int count = 0;
  if (n == 2 && r[1] < r[0]) std::swap(r[0], r[1]);
  for (int i = 0; i < n; ++i) {
    if (r[i] > lo && r[i] < hi && (count == 0 || r[i] > out[count - 1])) out[count++] = r[i];
  }
  return count;
}

// Root of the monotone f in [a, b] with f(a), f(b) of opposite signs.
double refine(const Cubic& f, double a, double b, double fa, double fb, RootMethod method, RootStats* stats) {
  double t = a - fa * (b - a) / (fb - fa);  // regula falsi start
  for (int it = 0; it < 100; ++it) {
    const double ft = f(t);
    if (ft == 0.0) return t;
    if ((ft < 0.0) == (fa < 0.0)) {
      a = t;
      fa = ft;
    } else {
      b = t;
    }
    const double d1 = f.derivative(t);
    double next;
    if (method == RootMethod::Halley) {
      // pd-dd eq. 25: t <- t - 2 f f' / (2 f'^2 - f f'').
      const double denom = 2.0 * d1 * d1 - ft * f.second(t);
      next = denom != 0.0 ? t - 2.0 * ft * d1 / denom : 0.5 * (a + b);
    } else {
      next = d1 != 0.0 ? t - ft / d1 : 0.5 * (a + b);
    }
    if (!(next > a && next < b)) next = 0.5 * (a + b);  // safeguard: stay inside the bracket
    if (stats) ++stats->iterations;
    if (std::abs(next - t) <= 1e-15 * std::max(1.0, std::abs(t)) || b - a <= 1e-15) return next;
    t = next;
  }
  return t;
}

}  // namespace

Cubic tripleProductCubic(const Eigen::Vector3d& a, const Eigen::Vector3d& da, const Eigen::Vector3d& b,
                         const Eigen::Vector3d& db, const Eigen::Vector3d& c, const Eigen::Vector3d& dc) {
  auto det = [](const Eigen::Vector3d& x, const Eigen::Vector3d& y, const Eigen::Vector3d& z) {
    return x.cross(y).dot(z);
  };
  Cubic f;
  f.c[0] = det(a, b, c);
  f.c[1] = det(da, b, c) + det(a, db, c) + det(a, b, dc);
  f.c[2] = det(da, db, c) + det(da, b, dc) + det(a, db, dc);
  f.c[3] = det(da, db, dc);
  return f;
}

int cubicRoots(const Cubic& f, double lo, double hi, RootMethod method, std::array<double, 3>& roots,
               RootStats* stats, double zeroTolerance) {
  const double zero = zeroTolerance * f.scale();
  std::array<double, 4> points{lo};
  std::array<double, 2> crit{};
  const int nc = criticalPoints(f, lo, hi, crit);
  for (int i = 0; i < nc; ++i) points[1 + i] = crit[i];
  points[1 + nc] = hi;
  int count = 0;
  auto push = [&](double t) {
    if (count < 3 && (count == 0 || t > roots[count - 1] + 1e-13)) roots[count++] = t;
  };
  for (int k = 0; k <= nc; ++k) {
    const double s = points[k];
    const double e = points[k + 1];
    const double fs = f(s);
    const double fe = f(e);
    if (stats) ++stats->intervals;
    if (std::abs(fs) <= zero) {
      push(s);  // root at the start (a touching root when s is a critical point)
    } else if (std::abs(fe) > zero && (fs < 0.0) != (fe < 0.0)) {
      push(refine(f, s, e, fs, fe, method, stats));
    }
  }
  if (std::abs(f(hi)) <= zero) push(hi);
  return count;
}

namespace {

// Earliest root t of f at which touching(t) holds; degenerate (identically coplanar) motion is sampled.
template <class Touching>
CcdResult earliestContact(const Cubic& f, double lengthScale, const CcdOptions& options, Touching&& touching) {
  CcdResult result;
  if (f.scale() <= 1e-24 * lengthScale * lengthScale * lengthScale) {
    constexpr int samples = 256;
    for (int i = 0; i <= samples; ++i) {
      const double t = double(i) / samples;
      if (touching(t)) {
        result.hit = true;
        result.t = t;
        return result;
      }
    }
    return result;
  }
  std::array<double, 3> roots{};
  const int n = cubicRoots(f, 0.0, 1.0, options.method, roots, &result.stats);
  for (int i = 0; i < n; ++i) {
    if (touching(roots[i])) {
      result.hit = true;
      result.t = roots[i];
      return result;
    }
  }
  return result;
}

}  // namespace

CcdResult vertexTriangleCcd(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c, const Eigen::Vector3d& dp, const Eigen::Vector3d& da,
                            const Eigen::Vector3d& db, const Eigen::Vector3d& dc, const CcdOptions& options) {
  const Cubic f = tripleProductCubic(b - a, db - da, c - a, dc - da, p - a, dp - da);
  const double scale = std::max({(b - a).norm(), (c - a).norm(), (p - a).norm(), (dp - da).norm(), (db - da).norm(),
                                 (dc - da).norm(), 1e-30});
  const double tol2 = options.tolerance * options.tolerance;
  return earliestContact(f, scale, options, [&](double t) {
    return closestPointTriangle(p + t * dp, a + t * da, b + t * db, c + t * dc).distanceSquared <= tol2;
  });
}

CcdResult edgeEdgeCcd(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                      const Eigen::Vector3d& q1, const Eigen::Vector3d& dp0, const Eigen::Vector3d& dp1,
                      const Eigen::Vector3d& dq0, const Eigen::Vector3d& dq1, const CcdOptions& options) {
  const Cubic f = tripleProductCubic(p1 - p0, dp1 - dp0, q0 - p0, dq0 - dp0, q1 - p0, dq1 - dp0);
  const double scale = std::max({(p1 - p0).norm(), (q0 - p0).norm(), (q1 - p0).norm(), (dp1 - dp0).norm(),
                                 (dq0 - dp0).norm(), (dq1 - dp0).norm(), 1e-30});
  const double tol2 = options.tolerance * options.tolerance;
  return earliestContact(f, scale, options, [&](double t) {
    return closestPointsEdgeEdge(p0 + t * dp0, p1 + t * dp1, q0 + t * dq0, q1 + t * dq1).distanceSquared <= tol2;
  });
}

}  // namespace drape::collision
