#pragma once
// Finite-difference check of a Newton drape energy, shared by the energy tests: the gradient against central
// differences of the value, the assembled Hessian against central differences of the gradient (exact Hessians) or
// for positive semi-definiteness (projected ones), and its symmetry.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <utility>
#include <vector>

#include "drape/newton/block_matrix.h"
#include "drape/newton/energy.h"

namespace drape::newton {

inline Eigen::VectorXd gradientOf(const Energy& e, const Eigen::VectorXd& x) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  e.addGradient(x, g);
  return g;
}

// Central differences of value -> gradient and of gradient -> Hessian, compared by relative Frobenius error.
inline void checkEnergy(Energy& e, const Eigen::VectorXd& x, bool checkHessian, double step = 1e-6) {
  const int n = static_cast<int>(x.size());
  Eigen::VectorXd g = gradientOf(e, x), gfd(n);
  Eigen::MatrixXd hfd(n, n);
  for (int k = 0; k < n; ++k) {
    Eigen::VectorXd xp = x, xm = x;
    xp(k) += step;
    xm(k) -= step;
    gfd(k) = (e.value(xp) - e.value(xm)) / (2 * step);
    hfd.col(k) = (gradientOf(e, xp) - gradientOf(e, xm)) / (2 * step);
  }
  ASSERT_GT(g.norm(), 0.0) << e.name();
  EXPECT_LT((g - gfd).norm() / gfd.norm(), 1e-5) << e.name();
  BlockMatrix h;
  std::vector<std::pair<int, int>> pairs;
  e.addCouplings(pairs);
  h.build(n / 3, pairs);
  e.addHessian(x, h);
  Eigen::MatrixXd hd = Eigen::MatrixXd(h.toSparse());
  EXPECT_LT((hd - hd.transpose()).norm(), 1e-12 * (1.0 + hd.norm())) << e.name() << ": Hessian not symmetric";
  if (checkHessian) {
    ASSERT_GT(hfd.norm(), 0.0);
    EXPECT_LT((hd - hfd).norm() / hfd.norm(), 1e-4) << e.name();
  }
  // Every assembled Hessian is SPD up to round-off (the solver relies on it).
  if (!checkHessian) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(hd);
    EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-9 * eig.eigenvalues().cwiseAbs().maxCoeff()) << e.name();
  }
}

}  // namespace drape::newton
