#include "drape/pd/strain_projection.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace drape::pd {
namespace {

// Any unit vector orthogonal to u (unit).
Eigen::Vector3d anyOrthogonal(const Eigen::Vector3d& u) {
  const Eigen::Vector3d axis = std::abs(u.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return u.cross(axis).normalized();
}

// Relative determinant of F^T F (det / trace^2 = l_min l_max / (l_min + l_max)^2) above which the closed-form
// polar decomposition is used: below it, cancellation in det would cost more than 1e-10 relative accuracy.
constexpr double kClosedFormPolarMinDet = 1e-6;

// Polar rotation of a thin F (3 x 2) by an eigen decomposition of F^T F; on a (nearly) collapsed F, where
// rounding in F^T F would leave that rotation's columns visibly non-orthonormal (singular values more than 1e4
// apart), an orthonormal frame from its longer column, the other completed in its plane.
Eigen::Matrix<double, 3, 2> polarFrameNearCollapse(const Eigen::Matrix<double, 3, 2>& f) {
  const Eigen::Matrix2d c = f.transpose() * f;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig;
  eig.computeDirect(c);
  const Eigen::Vector2d lambda = eig.eigenvalues().cwiseMax(0.0);
  const Eigen::Matrix2d v = eig.eigenvectors();
  const double scale = std::max(c.trace(), 1e-300);
  if (lambda.minCoeff() > 1e-8 * scale) {
    const Eigen::Vector2d inv = lambda.cwiseSqrt().cwiseInverse();
    return f * v * inv.asDiagonal() * v.transpose();
  }
  Eigen::Matrix<double, 3, 2> r;
  const int longer = f.col(0).squaredNorm() >= f.col(1).squaredNorm() ? 0 : 1;
  const int other = 1 - longer;
  Eigen::Vector3d u = f.col(longer);
  u = u.norm() > 1e-150 ? Eigen::Vector3d(u.normalized()) : Eigen::Vector3d::UnitX();
  Eigen::Vector3d w = f.col(other) - u.dot(f.col(other)) * u;
  w = w.norm() > 1e-12 * std::sqrt(scale) ? Eigen::Vector3d(w.normalized()) : anyOrthogonal(u);
  w = (w - u.dot(w) * u).normalized();  // a second Gram-Schmidt pass: w came from a near-cancellation
  r.col(longer) = u;
  r.col(other) = w;
  return r;
}

// Polar decomposition F = R S (R 3 x 2 with orthonormal columns, S symmetric 2 x 2). C = F^T F = [a b; b c]. Away
// from collapse its square root has a closed form (Cayley-Hamilton for 2 x 2): S = (C + sqrt(det C) I) /
// sqrt(tr C + 2 sqrt(det C)), and R = F S^-1. This runs for every triangle in every L-G iteration, at a fraction
// of the cost of an eigen decomposition.
void polarDecomposition(const Eigen::Matrix<double, 3, 2>& f, Eigen::Matrix<double, 3, 2>& r, Eigen::Matrix2d& s) {
  const double a = f.col(0).squaredNorm(), b = f.col(0).dot(f.col(1)), c = f.col(1).squaredNorm();
  const double det = a * c - b * b, trace = a + c;
  if (det > kClosedFormPolarMinDet * trace * trace) {
    const double root = std::sqrt(det), invT = 1.0 / std::sqrt(trace + 2.0 * root);
    s << (a + root) * invT, b * invT, b * invT, (c + root) * invT;
    Eigen::Matrix2d sInv;  // adj(S) / det S, det S = root
    sInv << (c + root), -b, -b, (a + root);
    sInv *= invT / root;
    r = f * sInv;
  } else {
    r = polarFrameNearCollapse(f);
    s = r.transpose() * f;
  }
}

// S with its diagonal clamped into the stretch limits (and, when the stretch holds the shear, its off-diagonal
// into +-shearLimit).
Eigen::Matrix2d clampedStretch(const Eigen::Matrix2d& s, const StretchLimits& warp, const StretchLimits& weft,
                               double shearLimit, bool stretchHoldsShear) {
  Eigen::Matrix2d stretch = s;
  stretch(0, 0) = std::clamp(s(0, 0), warp.min, warp.max);
  stretch(1, 1) = std::clamp(s(1, 1), weft.min, weft.max);
  if (stretchHoldsShear)
    stretch(0, 1) = stretch(1, 0) = std::clamp(0.5 * (s(0, 1) + s(1, 0)), -shearLimit, shearLimit);
  return stretch;
}

}  // namespace

StrainProjection projectStrain(const Eigen::Matrix<double, 3, 2>& f, const StretchLimits& warp,
                               const StretchLimits& weft, double shearLimit, bool stretchHoldsShear) {
  Eigen::Matrix<double, 3, 2> r;
  Eigen::Matrix2d s;
  polarDecomposition(f, r, s);
  Eigen::Matrix2d shear = s;
  shear(0, 1) = shear(1, 0) = std::clamp(0.5 * (s(0, 1) + s(1, 0)), -shearLimit, shearLimit);
  return {r * clampedStretch(s, warp, weft, shearLimit, stretchHoldsShear), r * shear};
}

Eigen::Matrix<double, 3, 2> combinedTarget(const StrainConstraint& sc, const StrainProjection& p) {
  Eigen::Matrix<double, 3, 2> out;
  for (int c = 0; c < 2; ++c) {
    const double ws = c == 0 ? sc.weightWarp : sc.weightWeft;
    const double total = ws + sc.weightShear;
    out.col(c) = total > 0.0 ? Eigen::Vector3d((ws * p.stretch.col(c) + sc.weightShear * p.shear.col(c)) / total)
                             : Eigen::Vector3d(p.stretch.col(c));
  }
  return out;
}

double strainEnergy(const StrainConstraint& sc, const Eigen::Matrix<double, 3, 2>& f, const StretchLimits& warp,
                    const StretchLimits& weft, double shearLimit, bool stretchHoldsShear) {
  const StrainProjection p = projectStrain(f, warp, weft, shearLimit, stretchHoldsShear);
  const Eigen::Matrix<double, 3, 2> ds = f - p.stretch, dh = f - p.shear;
  return 0.5 * (sc.weightWarp * ds.col(0).squaredNorm() + sc.weightWeft * ds.col(1).squaredNorm() +
                sc.weightShear * dh.squaredNorm());
}

Eigen::Matrix<double, 3, 2> strainTarget(const StrainConstraint& sc, const Eigen::Matrix<double, 3, 2>& f,
                                         const StretchLimits& warp, const StretchLimits& weft, double shearLimit,
                                         bool stretchHoldsShear) {
  if (sc.weightShear != 0.0) return combinedTarget(sc, projectStrain(f, warp, weft, shearLimit, stretchHoldsShear));
  // No shear constraint (the stretch holds the shear, or a degenerate rest triangle): the target is the stretch
  // projection alone (combinedTarget's weighted mean of one term).
  Eigen::Matrix<double, 3, 2> r;
  Eigen::Matrix2d s;
  polarDecomposition(f, r, s);
  return r * clampedStretch(s, warp, weft, shearLimit, stretchHoldsShear);
}

void strainTargets(const std::vector<StrainConstraint>& strains, const Eigen::MatrixX3d& x, int begin, int end,
                   const StretchLimits& warp, const StretchLimits& weft, double shearLimit, bool stretchHoldsShear,
                   Eigen::Matrix<double, 3, 2>* out) {
  // Structure of arrays over a batch: F's six entries (rows 0-2 warp column, 3-5 weft column) and the targets.
  constexpr int kBatch = 8;
  const double* coordinate[3] = {x.col(0).data(), x.col(1).data(), x.col(2).data()};
  alignas(64) double f[6][kBatch];
  alignas(64) double p[6][kBatch];
  alignas(64) double closedForm[kBatch];
  // The off-diagonal of S is clamped only when the stretch holds the shear.
  const double unbounded = std::numeric_limits<double>::infinity();
  const double shearMin = stretchHoldsShear ? -shearLimit : -unbounded;
  const double shearMax = stretchHoldsShear ? shearLimit : unbounded;
  const double warpMin = warp.min, warpMax = warp.max, weftMin = weft.min, weftMax = weft.max;
  for (int first = begin; first < end; first += kBatch) {
    const int count = std::min(kBatch, end - first);
    for (int k = 0; k < kBatch; ++k) {
      if (k >= count) {  // padding: the identity, whose lanes are computed and dropped
        for (int r = 0; r < 6; ++r) f[r][k] = r == 0 || r == 4 ? 1.0 : 0.0;
        continue;
      }
      const StrainConstraint& sc = strains[first + k];
      for (int r = 0; r < 3; ++r) {
        const double x0 = coordinate[r][sc.vertices[0]], x1 = coordinate[r][sc.vertices[1]];
        const double x2 = coordinate[r][sc.vertices[2]];
        f[r][k] = x0 * sc.g(0, 0) + x1 * sc.g(1, 0) + x2 * sc.g(2, 0);
        f[3 + r][k] = x0 * sc.g(0, 1) + x1 * sc.g(1, 1) + x2 * sc.g(2, 1);
      }
    }
    // polarDecomposition's closed form and clampedStretch, lane by lane without branches.
    for (int k = 0; k < kBatch; ++k) {
      const double a = f[0][k] * f[0][k] + f[1][k] * f[1][k] + f[2][k] * f[2][k];
      const double b = f[0][k] * f[3][k] + f[1][k] * f[4][k] + f[2][k] * f[5][k];
      const double c = f[3][k] * f[3][k] + f[4][k] * f[4][k] + f[5][k] * f[5][k];
      const double det = a * c - b * b, trace = a + c;
      closedForm[k] = det > kClosedFormPolarMinDet * trace * trace ? 1.0 : 0.0;
      // |det| + 1e-300: finite in the dropped lanes, equal to det in the kept ones (std::max would stop GCC's
      // vectoriser).
      const double root = std::sqrt(std::abs(det) + 1e-300);
      const double invT = 1.0 / std::sqrt(trace + 2.0 * root);
      const double q = invT / root;  // S^-1 = adj(S) / det S, det S = root
      const double inv00 = (c + root) * q, inv01 = -b * q, inv11 = (a + root) * q;
      const double s00 = std::min(std::max((a + root) * invT, warpMin), warpMax);
      const double s11 = std::min(std::max((c + root) * invT, weftMin), weftMax);
      const double s01 = std::min(std::max(b * invT, shearMin), shearMax);
      const double r00 = f[0][k] * inv00 + f[3][k] * inv01, r01 = f[0][k] * inv01 + f[3][k] * inv11;
      const double r10 = f[1][k] * inv00 + f[4][k] * inv01, r11 = f[1][k] * inv01 + f[4][k] * inv11;
      const double r20 = f[2][k] * inv00 + f[5][k] * inv01, r21 = f[2][k] * inv01 + f[5][k] * inv11;
      p[0][k] = r00 * s00 + r01 * s01;
      p[1][k] = r10 * s00 + r11 * s01;
      p[2][k] = r20 * s00 + r21 * s01;
      p[3][k] = r00 * s01 + r01 * s11;
      p[4][k] = r10 * s01 + r11 * s11;
      p[5][k] = r20 * s01 + r21 * s11;
    }
    for (int k = 0; k < count; ++k) {
      const StrainConstraint& sc = strains[first + k];
      Eigen::Matrix<double, 3, 2>& target = out[first + k - begin];
      if (closedForm[k] == 0.0 || sc.weightShear != 0.0) {
        Eigen::Matrix<double, 3, 2> fk;
        for (int r = 0; r < 6; ++r) fk(r % 3, r / 3) = f[r][k];
        target = strainTarget(sc, fk, warp, weft, shearLimit, stretchHoldsShear);
      } else {
        for (int r = 0; r < 6; ++r) target(r % 3, r / 3) = p[r][k];
      }
    }
  }
}

}  // namespace drape::pd
