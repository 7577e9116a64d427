#include "drape/pd/contact_solve.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/SparseCore>

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

// Dual steepest descent (header) from mu0 (m x 3), with y0 = K^-1 S^T mu0: returns dx = K^-1 S^T mu after at
// most `iterations` updates; done: updates made.
Eigen::MatrixX3d dualSteepestDescent(const Eigen::SparseMatrix<double>& k, const GlobalSolver& solver,
                                     const ContactSet& c, const Eigen::MatrixX3d& x, int iterations,
                                     double tolerance, const Eigen::Array3d& norm0, const Eigen::MatrixX3d& mu0,
                                     const Eigen::MatrixX3d& y0, int& done) {
  const int m = c.size();
  const int n = static_cast<int>(x.rows());
  Eigen::VectorXd w(m), invW(m), precond(m);
  for (int i = 0; i < m; ++i) {
    w[i] = c.weights[i];
    invW[i] = 1.0 / w[i];
    precond[i] = 1.0 / (invW[i] + 1.0 / std::max(k.coeff(c.dofs[i], c.dofs[i]), 1e-300));
  }
  Eigen::MatrixX3d y = y0;
  Eigen::MatrixX3d r = c.targets - gather(c, x) - invW.asDiagonal() * mu0 - gather(c, y0);  // g - A mu0
  for (done = 0; done < iterations; ++done) {
    // Residual of eq. 14 = W r (on the contacts); stop when PCG would have nothing to do.
    if (relative(w.asDiagonal() * r, norm0) <= tolerance) break;
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

// K_cc: the rows and columns of k at the contact DOFs (m x m, SPD as a principal block of k).
Eigen::SparseMatrix<double> contactBlock(const Eigen::SparseMatrix<double>& k, const ContactSet& c) {
  std::vector<int> index(k.rows(), -1);
  for (int i = 0; i < c.size(); ++i) index[c.dofs[i]] = i;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(c.size()) * 8);
  for (int i = 0; i < c.size(); ++i)
    for (Eigen::SparseMatrix<double>::InnerIterator e(k, c.dofs[i]); e; ++e)
      if (index[e.row()] >= 0) entries.emplace_back(index[e.row()], i, e.value());
  Eigen::SparseMatrix<double> kcc(c.size(), c.size());
  kcc.setFromTriplets(entries.begin(), entries.end());
  return kcc;
}

// Conjugate gradients on the dual A mu = g (header), preconditioned by K_cc, from mu0 with y0 = K^-1 S^T mu0.
// Returns dx = K^-1 S^T mu after at most `iterations` updates; done: updates made.
Eigen::MatrixX3d dualConjugateGradients(const Eigen::SparseMatrix<double>& k, const GlobalSolver& solver,
                                        const ContactSet& c, const Eigen::MatrixX3d& x, int iterations,
                                        double tolerance, const Eigen::Array3d& norm0, const Eigen::MatrixX3d& mu0,
                                        const Eigen::MatrixX3d& y0, int& done) {
  const int m = c.size();
  const int n = static_cast<int>(x.rows());
  Eigen::VectorXd w(m), invW(m);
  for (int i = 0; i < m; ++i) {
    w[i] = c.weights[i];
    invW[i] = 1.0 / w[i];
  }
  const Eigen::SparseMatrix<double> kcc = contactBlock(k, c);
  Eigen::MatrixX3d y = y0;
  Eigen::MatrixX3d r = c.targets - gather(c, x) - invW.asDiagonal() * mu0 - gather(c, y0);  // g - A mu0
  Eigen::MatrixX3d z = kcc * r, p = z;
  Eigen::Array3d rz = (r.array() * z.array()).colwise().sum().transpose();
  for (done = 0; done < iterations; ++done) {
    if (relative(w.asDiagonal() * r, norm0) <= tolerance) break;  // W r: the residual of eq. 14
    const Eigen::MatrixX3d q = spread(solver, c, n, p);
    const Eigen::MatrixX3d ap = invW.asDiagonal() * p + gather(c, q);
    const Eigen::Array3d pap = (p.array() * ap.array()).colwise().sum().transpose();
    Eigen::Array3d alpha = Eigen::Array3d::Zero();
    for (int col = 0; col < 3; ++col)
      if (pap[col] > 0.0) alpha[col] = rz[col] / pap[col];
    y += q * alpha.matrix().asDiagonal();
    r -= ap * alpha.matrix().asDiagonal();
    z = kcc * r;
    const Eigen::Array3d rzNew = (r.array() * z.array()).colwise().sum().transpose();
    Eigen::Array3d beta = Eigen::Array3d::Zero();
    for (int col = 0; col < 3; ++col)
      if (rz[col] > 0.0) beta[col] = rzNew[col] / rz[col];
    rz = rzNew;
    p = z + p * beta.matrix().asDiagonal();
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

int contactChurn(const std::vector<int>& previous, const ContactSet& current, std::vector<char>& scratch) {
  int maxDof = -1;
  for (int d : previous) maxDof = std::max(maxDof, d);
  for (int d : current.dofs) maxDof = std::max(maxDof, d);
  if (static_cast<int>(scratch.size()) <= maxDof) scratch.resize(maxDof + 1, 0);
  for (int d : previous) scratch[d] = 1;
  int churn = 0;
  for (int d : current.dofs) {
    if (scratch[d] == 1) scratch[d] = 2;  // in both
    else if (scratch[d] == 0) ++churn;    // joined
  }
  for (int d : previous) {
    churn += scratch[d] == 1;  // left
    scratch[d] = 0;
  }
  return churn;
}

ContactSolveStats solveWithContacts(const Eigen::SparseMatrix<double>& k, const GlobalSolver& solver,
                                    const ContactSet& contacts, ContactSolveKind kind, int maxPcgIterations,
                                    double pcgTolerance, Eigen::MatrixX3d& x, int sdIterations,
                                    ContactWarmStart* warm, int maxDualIterations) {
  ContactSolveStats stats;
  const int n = static_cast<int>(x.rows());
  const int m = contacts.size();
  if (m == 0) {
    if (warm) warm->clear();
    return stats;
  }
  // Right-hand side of eq. 14: Delta b - Delta K x, supported on the colliding DOFs only.
  Eigen::MatrixX3d r0 = Eigen::MatrixX3d::Zero(n, 3);
  for (int i = 0; i < m; ++i)
    r0.row(contacts.dofs[i]) = contacts.weights[i] * (contacts.targets.row(i) - x.row(contacts.dofs[i]));
  const Eigen::Array3d norm0 = r0.colwise().norm().transpose().array().max(1e-300);
  // Warm start: mu0 = the kept forces of the DOFs still in contact, y0 = K^-1 S^T mu0.
  Eigen::MatrixX3d mu0 = Eigen::MatrixX3d::Zero(m, 3), y0 = Eigen::MatrixX3d::Zero(n, 3);
  if (warm && warm->force.rows() == n) {
    bool any = false;
    for (int i = 0; i < m; ++i) {
      mu0.row(i) = warm->force.row(contacts.dofs[i]);
      any = any || !mu0.row(i).isZero();
    }
    if (any) {
      y0 = spread(solver, contacts, n, mu0);
      // Residual of eq. 14 at dx = y0: W (g - W^-1 mu0 - S y0), on the contacts only (K y0 = S^T mu0).
      Eigen::MatrixX3d rw(m, 3);
      for (int i = 0; i < m; ++i)
        rw.row(i) = contacts.weights[i] * (contacts.targets.row(i) - x.row(contacts.dofs[i]) - y0.row(contacts.dofs[i])) -
                    mu0.row(i);
      // Whole-residual comparison (one coordinate's residual at dx = 0 can be tiny, e.g. tangential).
      stats.warmRelativeResidual = rw.norm() / std::max(r0.norm(), 1e-300);
      if (!(stats.warmRelativeResidual < 1.0)) {  // worse than no warm start: drop it
        mu0.setZero();
        y0.setZero();
      }
    }
  }
  Eigen::MatrixX3d dx = y0;
  if (kind == ContactSolveKind::DualThenPcg)
    dx = dualSteepestDescent(k, solver, contacts, x, std::max(sdIterations, 1), pcgTolerance, norm0, mu0, y0,
                             stats.sdIterations);
  else if (kind == ContactSolveKind::DualCgThenPcg)
    dx = dualConjugateGradients(k, solver, contacts, x, std::max(maxDualIterations, 1), pcgTolerance, norm0, mu0,
                                y0, stats.sdIterations);
  // PCG on eq. 14 preconditioned by K^-1, one CG per coordinate column.
  Eigen::MatrixX3d res = r0 - applySystem(k, contacts, dx);
  double rel = relative(res, norm0);
  stats.sdRelativeResidual = kind == ContactSolveKind::Pcg ? 1.0 : rel;
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
  if (warm) {  // the constraint forces w_k (p_k - x_k) at the new positions
    warm->force = Eigen::MatrixX3d::Zero(n, 3);
    if (x.allFinite())
      for (int i = 0; i < m; ++i)
        warm->force.row(contacts.dofs[i]) = contacts.weights[i] * (contacts.targets.row(i) - x.row(contacts.dofs[i]));
  }
  return stats;
}

}  // namespace drape::pd
