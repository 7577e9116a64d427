#include "drape/pd/contact_solve.h"

#include <cmath>

namespace drape::pd {
namespace {

// y = (K + Delta K) v.
Eigen::MatrixX3d applySystem(const Eigen::SparseMatrix<double>& k, const ContactSet& c, const Eigen::MatrixX3d& v) {
  Eigen::MatrixX3d y = k * v;
  for (int i = 0; i < c.size(); ++i) y.row(c.dofs[i]) += c.weights[i] * v.row(c.dofs[i]);
  return y;
}

}  // namespace

ContactSolveStats solveWithContacts(const Eigen::SparseMatrix<double>& k, const GlobalSolver& solver,
                                    const ContactSet& contacts, ContactSolveKind kind, int maxPcgIterations,
                                    double pcgTolerance, Eigen::MatrixX3d& x) {
  ContactSolveStats stats;
  if (contacts.size() == 0) return stats;
  const int n = static_cast<int>(x.rows());
  // Right-hand side of eq. 14: Delta b - Delta K x, supported on the colliding DOFs only.
  Eigen::MatrixX3d r0 = Eigen::MatrixX3d::Zero(n, 3);
  for (int i = 0; i < contacts.size(); ++i)
    r0.row(contacts.dofs[i]) = contacts.weights[i] * (contacts.targets.row(i) - x.row(contacts.dofs[i]));
  Eigen::MatrixX3d dx = Eigen::MatrixX3d::Zero(n, 3);
  if (kind == ContactSolveKind::DualThenPcg) {
    // Eq. 24 with lambda_0 = d and the residual of eq. 23: S dx = (p - x) / (1 + w_i / w_k).
    Eigen::MatrixX3d force = r0;
    for (int i = 0; i < contacts.size(); ++i) {
      const int d = contacts.dofs[i];
      const double eps = k.coeff(d, d) / contacts.weights[i];
      const Eigen::RowVector3d dxk = (contacts.targets.row(i) - x.row(d)) / (1.0 + eps);
      force.row(d) -= contacts.weights[i] * dxk;  // Delta b - Delta K (x + dx) at the contact
    }
    solver.solve(force, dx);  // the rest of the cloth follows: K dx = r0 - Delta K dx_hat
    stats.sdIterations = 1;
  }
  // PCG on eq. 14 preconditioned by K^-1, one CG per coordinate column.
  Eigen::MatrixX3d res = r0 - applySystem(k, contacts, dx);
  const Eigen::Array3d norm0 = r0.colwise().norm().transpose().array().max(1e-300);
  Eigen::MatrixX3d z, p, ap;
  solver.solve(res, z);
  p = z;
  Eigen::Array3d rz = (res.array() * z.array()).colwise().sum().transpose();
  double rel = (res.colwise().norm().transpose().array() / norm0).maxCoeff();
  int it = 0;
  while (it < maxPcgIterations && rel > pcgTolerance) {
    ap = applySystem(k, contacts, p);
    const Eigen::Array3d pap = (p.array() * ap.array()).colwise().sum().transpose();
    Eigen::Array3d alpha = Eigen::Array3d::Zero();
    for (int c = 0; c < 3; ++c)
      if (pap[c] > 0.0) alpha[c] = rz[c] / pap[c];
    dx += p * alpha.matrix().asDiagonal();
    res -= ap * alpha.matrix().asDiagonal();
    ++it;
    rel = (res.colwise().norm().transpose().array() / norm0).maxCoeff();
    if (!(rel > pcgTolerance)) break;
    solver.solve(res, z);
    const Eigen::Array3d rzNew = (res.array() * z.array()).colwise().sum().transpose();
    Eigen::Array3d beta = Eigen::Array3d::Zero();
    for (int c = 0; c < 3; ++c)
      if (rz[c] > 0.0) beta[c] = rzNew[c] / rz[c];
    rz = rzNew;
    p = z + p * beta.matrix().asDiagonal();
  }
  stats.pcgIterations = it;
  stats.relativeResidual = std::isfinite(rel) ? rel : 1.0;
  x += dx;
  return stats;
}

}  // namespace drape::pd
