#pragma once
// Continuous collision detection for the PD preview (pd-dd section 7.3). Vertices move linearly over the step,
// x(t) = x + t dx for t in [0, 1]. A vertex-triangle or edge-edge pair can only touch when its four points are
// coplanar, the roots of a cubic f(t) (a triple product). The cubic is split at the roots of f' into intervals
// where it is monotone (as in Yuksel 2022), each sign change is refined by Halley's method (pd-dd eq. 25) or by
// Newton's method (baseline), safeguarded by bisection, and the earliest root at which the primitives actually
// touch is the time of impact.
#include <Eigen/Core>
#include <array>
#include <cmath>

namespace drape::collision {

enum class RootMethod { Halley, Newton };

// f(t) = c[0] + c[1] t + c[2] t^2 + c[3] t^3.
struct Cubic {
  std::array<double, 4> c{};
  double operator()(double t) const { return ((c[3] * t + c[2]) * t + c[1]) * t + c[0]; }
  double derivative(double t) const { return (3.0 * c[3] * t + 2.0 * c[2]) * t + c[1]; }
  double second(double t) const { return 6.0 * c[3] * t + 2.0 * c[2]; }
  double scale() const { return std::abs(c[0]) + std::abs(c[1]) + std::abs(c[2]) + std::abs(c[3]); }
};

// det(a + t da, b + t db, c + t dc) as a cubic in t.
Cubic tripleProductCubic(const Eigen::Vector3d& a, const Eigen::Vector3d& da, const Eigen::Vector3d& b,
                         const Eigen::Vector3d& db, const Eigen::Vector3d& c, const Eigen::Vector3d& dc);

struct RootStats {
  int iterations = 0;  // Halley or Newton updates, summed over intervals
  int intervals = 0;   // monotone intervals examined
};

// Roots of f in [lo, hi], increasing, at most 3: sign changes on each monotone interval plus touching (double)
// roots where |f| at a critical point is below zeroTolerance * f.scale(). Returns the count written to roots.
int cubicRoots(const Cubic& f, double lo, double hi, RootMethod method, std::array<double, 3>& roots,
               RootStats* stats = nullptr, double zeroTolerance = 1e-12);

struct CcdOptions {
  RootMethod method = RootMethod::Halley;
  double tolerance = 1e-6;  // contact distance accepted at a coplanarity root, metres
};

struct CcdResult {
  bool hit = false;
  double t = 1.0;  // time of impact in [0, 1] when hit
  RootStats stats;
};

// Vertex p against triangle (a, b, c); d*: displacements over the step.
CcdResult vertexTriangleCcd(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c, const Eigen::Vector3d& dp, const Eigen::Vector3d& da,
                            const Eigen::Vector3d& db, const Eigen::Vector3d& dc, const CcdOptions& options = {});

// Edge (p0, p1) against edge (q0, q1).
CcdResult edgeEdgeCcd(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                      const Eigen::Vector3d& q1, const Eigen::Vector3d& dp0, const Eigen::Vector3d& dp1,
                      const Eigen::Vector3d& dq0, const Eigen::Vector3d& dq1, const CcdOptions& options = {});

}  // namespace drape::collision
