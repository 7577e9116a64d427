#include "drape/newton/linear_solve.h"

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/LU>
#include <cmath>
#include <vector>

namespace drape::newton {
namespace {

// Preconditioned conjugate gradients from x = 0; applyA(p, out), applyP(r, out). Returns the iteration count.
template <typename Vec, typename ApplyA, typename ApplyP>
int pcg(const ApplyA& applyA, const ApplyP& applyP, const Vec& b, Vec& x, double tol, int maxIt) {
  using S = typename Vec::Scalar;
  x.setZero(b.size());
  Vec r = b, z(b.size()), ap(b.size());
  double bNorm = static_cast<double>(b.norm());
  if (bNorm == 0.0) return 0;
  applyP(r, z);
  Vec p = z;
  S rz = r.dot(z);
  int it = 0;
  while (it < maxIt) {
    applyA(p, ap);
    S pap = p.dot(ap);
    if (!(std::abs(static_cast<double>(pap)) > 0.0)) break;
    S alpha = rz / pap;
    x += alpha * p;
    r -= alpha * ap;
    ++it;
    if (static_cast<double>(r.norm()) <= tol * bNorm) break;
    applyP(r, z);
    S rzNew = r.dot(z);
    p = z + (rzNew / rz) * p;
    rz = rzNew;
  }
  return it;
}

// Per-scalar-row inverse diagonal or per-block inverse 3x3 of A (including dynamic diagonal contributions).
template <typename S>
struct BlockPreconditioner {
  std::vector<Eigen::Matrix<S, 3, 3>> inv;
  BlockPreconditioner(const BlockMatrix& a, bool blocks) : inv(a.numBlocks()) {
    std::vector<Eigen::Matrix3d> diag(a.numBlocks());
    for (int i = 0; i < a.numBlocks(); ++i) diag[i] = a.diagonalBlock(i);
    for (const auto& e : a.dynamicEntries())
      if (e.i == e.j) diag[e.i] += e.block;
    for (int i = 0; i < a.numBlocks(); ++i) {
      Eigen::Matrix3d d = diag[i];
      if (!blocks) d = Eigen::Matrix3d(d.diagonal().asDiagonal());
      Eigen::Matrix3d di = d.inverse();
      if (!di.allFinite()) di = Eigen::Matrix3d::Identity();
      inv[i] = di.cast<S>();
    }
  }
  template <typename Vec>
  void operator()(const Vec& r, Vec& z) const {
    for (size_t i = 0; i < inv.size(); ++i) z.template segment<3>(3 * i) = inv[i] * r.template segment<3>(3 * i);
  }
};

}  // namespace

LinearSolveResult solveLinear(const BlockMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                              const LinearSolveOptions& options) {
  LinearSolveResult result;
  const double tol = options.tolerance;
  const int maxIt = options.maxIterations;
  if (options.kind == LinearSolverKind::Cholmod) {
    Eigen::SparseMatrix<double> s = a.toSparse();
    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> chol(s);
    if (chol.info() != Eigen::Success) return result;
    x = chol.solve(b);
  } else if (options.mixedPrecision) {
    Eigen::SparseMatrix<float, Eigen::RowMajor> s = a.toSparse().cast<float>();
    Eigen::VectorXf bf = b.cast<float>(), xf;
    auto applyA = [&s](const Eigen::VectorXf& p, Eigen::VectorXf& out) { out.noalias() = s * p; };
    if (options.preconditioner == Preconditioner::IncompleteCholesky) {
      Eigen::SparseMatrix<float> sc = s;
      Eigen::IncompleteCholesky<float> ic(sc);
      auto applyP = [&ic](const Eigen::VectorXf& r, Eigen::VectorXf& z) { z = ic.solve(r); };
      result.iterations = pcg(applyA, applyP, bf, xf, tol, maxIt);
    } else if (options.preconditioner == Preconditioner::None) {
      result.iterations = pcg(applyA, [](const Eigen::VectorXf& r, Eigen::VectorXf& z) { z = r; }, bf, xf, tol, maxIt);
    } else {
      BlockPreconditioner<float> pre(a, options.preconditioner == Preconditioner::BlockJacobi);
      result.iterations = pcg(applyA, pre, bf, xf, tol, maxIt);
    }
    x = xf.cast<double>();
  } else {
    auto applyA = [&a](const Eigen::VectorXd& p, Eigen::VectorXd& out) { a.multiply(p, out); };
    if (options.preconditioner == Preconditioner::IncompleteCholesky) {
      Eigen::SparseMatrix<double> s = a.toSparse();
      Eigen::IncompleteCholesky<double> ic(s);
      auto applyP = [&ic](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = ic.solve(r); };
      result.iterations = pcg(applyA, applyP, b, x, tol, maxIt);
    } else if (options.preconditioner == Preconditioner::None) {
      result.iterations = pcg(applyA, [](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = r; }, b, x, tol, maxIt);
    } else {
      BlockPreconditioner<double> pre(a, options.preconditioner == Preconditioner::BlockJacobi);
      result.iterations = pcg(applyA, pre, b, x, tol, maxIt);
    }
  }
  if (!x.allFinite()) return result;
  double bNorm = b.norm();
  result.relativeResidual = bNorm > 0.0 ? (a * x - b).norm() / bNorm : 0.0;
  result.ok = true;
  return result;
}

}  // namespace drape::newton
