#include "drape/pd/contact_solve.h"

#include <algorithm>
#include <cmath>

namespace drape::pd {
namespace {

// y = (K + Delta K) v.
Eigen::MatrixX3d applySystem(const Eigen::SparseMatrix<double>& k, const ContactSet& c, const Eigen::MatrixX3d& v) {
  Eigen::MatrixX3d y = k * v;
  for (int i = 0; i < c.size(); ++i) y.row(c.dofs[i]) += c.weights[i] * v.row(c.dofs[i]);
  return y;
}

// K^-1 S^T s: spreads per-contact values s (m x 3) over the whole cloth with one collision-free solve.
Eigen::MatrixX3d spread(const GlobalSolver& solver, const ContactSet& c, int n, const Eigen::MatrixX3d& s) {
  Eigen::MatrixX3d full = Eigen::MatrixX3d::Zero(n, 3);
  for (int i = 0; i < c.size(); ++i) full.row(c.dofs[i]) = s.row(i);
  Eigen::MatrixX3d out;
  solver.solve(full, out);
  return out;
}

// S y: rows of y at the contact DOFs.
Eigen::MatrixX3d gather(const ContactSet& c, const Eigen::MatrixX3d& y) {
  Eigen::MatrixX3d out(c.size(), 3);
  for (int i = 0; i < c.size(); ++i) out.row(i) = y.row(c.dofs[i]);
  return out;
}

// Max over coordinates of |res_c| / |r0_c|.
double relative(const Eigen::MatrixX3d& res, const Eigen::Array3d& norm0) {
  return (res.colwise().norm().transpose().array() / norm0).maxCoeff();
}

// Dual steepest descent (header): returns dx = K^-1 S^T mu after at most `iterations` updates from mu = 0;
// done: updates made.
Eigen::MatrixX3d dualSteepestDescent(const Eigen::SparseMatrix<double>& k, const GlobalSolver& solver,
                                     const ContactSet& c, const Eigen::MatrixX3d& x, int iterations,
                                     double tolerance, const Eigen::Array3d& norm0, int& done) {
  const int m = c.size();
  const int n = static_cast<int>(x.rows());
  Eigen::VectorXd w(m), invW(m), precond(m);
  for (int i = 0; i < m; ++i) {
    w[i] = c.weights[i];
    invW[i] = 1.0 / w[i];
    precond[i] = 1.0 / (invW[i] + 1.0 / std::max(k.coeff(c.dofs[i], c.dofs[i]), 1e-300));
  }
  Eigen::MatrixX3d y = Eigen::MatrixX3d::Zero(n, 3);
  Eigen::MatrixX3d r = c.targets - gather(c, x);  // dual residual g - A mu, mu = 0
  for (done = 0; done < iterations; ++done) {
    // Residual of eq. 14 = W r (on the contacts); stop when PCG would have nothing to do.
    if (done > 0 && relative(w.asDiagonal() * r, norm0) <= tolerance) break;
    const Eigen::MatrixX3d s = precond.asDiagonal() * r;  // the eq. 24 direction
    const Eigen::MatrixX3d z = spread(solver, c, n, s);
    const Eigen::MatrixX3d as = invW.asDiagonal() * s + gather(c, z);
    const Eigen::Array3d rs = (r.array() * s.array()).colwise().sum().transpose();
    const Eigen::Array3d sas = (s.array() * as.array()).colwise().sum().transpose();
    Eigen::Array3d alpha = Eigen::Array3d::Zero();
    for (int col = 0; col < 3; ++col)
      if (sas[col] > 0.0) alpha[col] = rs[col] / sas[col];
    y += z * alpha.matrix().asDiagonal();
    r -= as * alpha.matrix().asDiagonal();
  }
  return y;
}

}  // namespace

void ContactAccumulator::reset(int freeCount) {
  for (int d : m_touched) {
    m_weight[d] = 0.0;
    m_weightedTarget[d].setZero();
  }
  m_touched.clear();
  m_constraints = 0;
  if (static_cast<int>(m_weight.size()) != freeCount) {
    m_weight.assign(freeCount, 0.0);
    m_weightedTarget.assign(freeCount, Eigen::Vector3d::Zero());
  }
}

void ContactAccumulator::add(int dof, const Eigen::Vector3d& target, double weight) {
  if (m_weight[dof] == 0.0) m_touched.push_back(dof);
  m_weight[dof] += weight;
  m_weightedTarget[dof] += weight * target;
  ++m_constraints;
}

ContactSet ContactAccumulator::merged() const {
  ContactSet set;
  set.dofs = m_touched;
  set.targets.resize(static_cast<int>(m_touched.size()), 3);
  set.weights.resize(m_touched.size());
  for (size_t i = 0; i < m_touched.size(); ++i) {
    const int d = m_touched[i];
    set.weights[i] = m_weight[d];
    set.targets.row(static_cast<int>(i)) = (m_weightedTarget[d] / m_weight[d]).transpose();
  }
  return set;
}

ContactSolveStats solveWithContacts(const Eigen::SparseMatrix<double>& k, const GlobalSolver& solver,
                                    const ContactSet& contacts, ContactSolveKind kind, int maxPcgIterations,
                                    double pcgTolerance, Eigen::MatrixX3d& x, int sdIterations) {
  ContactSolveStats stats;
  if (contacts.size() == 0) return stats;
  const int n = static_cast<int>(x.rows());
  // Right-hand side of eq. 14: Delta b - Delta K x, supported on the colliding DOFs only.
  Eigen::MatrixX3d r0 = Eigen::MatrixX3d::Zero(n, 3);
  for (int i = 0; i < contacts.size(); ++i)
    r0.row(contacts.dofs[i]) = contacts.weights[i] * (contacts.targets.row(i) - x.row(contacts.dofs[i]));
  const Eigen::Array3d norm0 = r0.colwise().norm().transpose().array().max(1e-300);
  Eigen::MatrixX3d dx = Eigen::MatrixX3d::Zero(n, 3);
  if (kind == ContactSolveKind::DualThenPcg)
    dx = dualSteepestDescent(k, solver, contacts, x, std::max(sdIterations, 1), pcgTolerance, norm0,
                             stats.sdIterations);
  // PCG on eq. 14 preconditioned by K^-1, one CG per coordinate column.
  Eigen::MatrixX3d res = r0 - applySystem(k, contacts, dx);
  double rel = relative(res, norm0);
  stats.sdRelativeResidual = kind == ContactSolveKind::DualThenPcg ? rel : 1.0;
  int it = 0;
  if (rel > pcgTolerance && maxPcgIterations > 0) {
    Eigen::MatrixX3d z, p, ap;
    solver.solve(res, z);
    p = z;
    Eigen::Array3d rz = (res.array() * z.array()).colwise().sum().transpose();
    while (it < maxPcgIterations && rel > pcgTolerance) {
      ap = applySystem(k, contacts, p);
      const Eigen::Array3d pap = (p.array() * ap.array()).colwise().sum().transpose();
      Eigen::Array3d alpha = Eigen::Array3d::Zero();
      for (int c = 0; c < 3; ++c)
        if (pap[c] > 0.0) alpha[c] = rz[c] / pap[c];
      dx += p * alpha.matrix().asDiagonal();
      res -= ap * alpha.matrix().asDiagonal();
      ++it;
      rel = relative(res, norm0);
      if (!(rel > pcgTolerance)) break;
      solver.solve(res, z);
      const Eigen::Array3d rzNew = (res.array() * z.array()).colwise().sum().transpose();
      Eigen::Array3d beta = Eigen::Array3d::Zero();
      for (int c = 0; c < 3; ++c)
        if (rz[c] > 0.0) beta[c] = rzNew[c] / rz[c];
      rz = rzNew;
      p = z + p * beta.matrix().asDiagonal();
    }
  }
  stats.pcgIterations = it;
  stats.relativeResidual = std::isfinite(rel) ? rel : 1.0;
  x += dx;
  return stats;
}

}  // namespace drape::pd
