// D(x) = min_u |r(x, u)|^2 with r = sum_i c_i(u) x_i, c affine in the free closest-point parameters u (the active
// set of the clamped minimisation is held fixed). With F(x, u) = |r|^2 and F_u = 0 at the minimiser:
//   grad D = F_x,   hess D = F_xx - F_xu F_uu^-1 F_ux,
//   F_x = 2 c (x) r,  F_xx = 2 (c c^T) (x) I3,  F_uu = 2 E^T E,  F_xu[:, j] = 2 (g_j (x) r + c (x) e_j),
// where g_j = dc/du_j and e_j = sum_i g_ji x_i (an edge vector).
#include "drape/collision/contact_stencil.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

namespace drape::collision {
namespace {

SquaredDistanceDerivatives derivatives(const std::array<Eigen::Vector3d, 4>& x, const Eigen::Vector4d& c,
                                       const Eigen::Vector4d* g, int freeCount) {
  SquaredDistanceDerivatives out;
  out.weights = c;
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) r += c[i] * x[i];
  out.value = r.squaredNorm();
  for (int i = 0; i < 4; ++i) out.gradient.segment<3>(3 * i) = 2.0 * c[i] * r;
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 4; ++k) out.hessian.block<3, 3>(3 * i, 3 * k) = 2.0 * c[i] * c[k] * Eigen::Matrix3d::Identity();
  }
  if (freeCount == 0) return out;
  Eigen::Matrix<double, 3, 2> E = Eigen::Matrix<double, 3, 2>::Zero();
  Eigen::Matrix<double, 12, 2> Fxu = Eigen::Matrix<double, 12, 2>::Zero();
  for (int j = 0; j < freeCount; ++j) {
    for (int i = 0; i < 4; ++i) E.col(j) += g[j][i] * x[i];
    for (int i = 0; i < 4; ++i) Fxu.block<3, 1>(3 * i, j) = 2.0 * (g[j][i] * r + c[i] * E.col(j));
  }
  if (freeCount == 1) {
    const double fuu = 2.0 * E.col(0).squaredNorm();
    if (fuu > 0.0) out.hessian -= Fxu.col(0) * Fxu.col(0).transpose() / fuu;
    return out;
  }
  const Eigen::Matrix2d Fuu = 2.0 * E.transpose() * E;
  const double det = Fuu.determinant();
  if (det > 1e-12 * Fuu(0, 0) * Fuu(1, 1)) {
    out.hessian -= Fxu * Fuu.inverse() * Fxu.transpose();
  } else if (Fuu(0, 0) > 0.0) {  // (nearly) parallel: keep one parameter free
    out.hessian -= Fxu.col(0) * Fxu.col(0).transpose() / Fuu(0, 0);
  }
  return out;
}

}  // namespace

SquaredDistanceDerivatives pointTriangleSquaredDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const PointTriangleResult r = closestPointTriangle(p, a, b, c);
  const Eigen::Vector3d& w = r.barycentric;
  const Eigen::Vector4d coeff(1.0, -w[0], -w[1], -w[2]);
  Eigen::Vector4d g[2];
  int freeCount = 0;
  switch (r.region) {
    case TriangleRegion::Face:
      g[0] = Eigen::Vector4d(0, 1, -1, 0);  // u0 = weight of b
      g[1] = Eigen::Vector4d(0, 1, 0, -1);  // u1 = weight of c
      freeCount = 2;
      break;
    case TriangleRegion::EdgeAB: g[0] = Eigen::Vector4d(0, 1, -1, 0); freeCount = 1; break;
    case TriangleRegion::EdgeBC: g[0] = Eigen::Vector4d(0, 0, 1, -1); freeCount = 1; break;
    case TriangleRegion::EdgeCA: g[0] = Eigen::Vector4d(0, -1, 0, 1); freeCount = 1; break;
    default: break;
  }
  return derivatives({p, a, b, c}, coeff, g, freeCount);
}

SquaredDistanceDerivatives edgeEdgeSquaredDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                   const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const EdgeEdgeResult r = closestPointsEdgeEdge(p0, p1, q0, q1);
  const Eigen::Vector4d coeff(1.0 - r.s, r.s, -(1.0 - r.t), -r.t);
  Eigen::Vector4d g[2];
  int freeCount = 0;
  if (r.s > 0.0 && r.s < 1.0) g[freeCount++] = Eigen::Vector4d(-1, 1, 0, 0);
  if (r.t > 0.0 && r.t < 1.0) g[freeCount++] = Eigen::Vector4d(0, 0, 1, -1);
  return derivatives({p0, p1, q0, q1}, coeff, g, freeCount);
}

template <int N>
Eigen::Matrix<double, N, N> projectPsd(const Eigen::Matrix<double, N, N>& m) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(m);
  const auto values = eig.eigenvalues().cwiseMax(0.0);
  return eig.eigenvectors() * values.asDiagonal() * eig.eigenvectors().transpose();
}
template Eigen::Matrix<double, 3, 3> projectPsd<3>(const Eigen::Matrix<double, 3, 3>&);
template Eigen::Matrix<double, 12, 12> projectPsd<12>(const Eigen::Matrix<double, 12, 12>&);

bool penaltyFromSquaredDistance(const SquaredDistanceDerivatives& D, double stiffness, double thickness,
                                bool projectToPsd, double& energy, Vector12d& gradient, Matrix12d& hessian) {
  const double d = std::sqrt(D.value);
  if (!(d < thickness) || d <= 0.0) return false;
  const double gap = thickness - d;
  // d = sqrt(D): grad d = grad D / (2d), hess d = hess D / (2d) - grad d grad d^T / d.
  const Vector12d gradD = D.gradient / (2.0 * d);
  const Matrix12d hessD = D.hessian / (2.0 * d) - gradD * gradD.transpose() / d;
  energy = 0.5 * stiffness * gap * gap;
  gradient = -stiffness * gap * gradD;
  hessian = stiffness * (gradD * gradD.transpose() - gap * hessD);
  if (projectToPsd) hessian = projectPsd<12>(hessian);
  return true;
}

}  // namespace drape::collision
