// The PCG's warm start (LinearSolveOptions::warmStart): a guess is taken as it is unless its best multiple (the one
// closest to the solution in the A-norm) is below 1/8, i.e. it points against the solution or is far too long; then
// it is taken with that multiple. Where the garment chatters, the Newton solver's guess (the last step's velocity
// change) is about minus the solution, and started from it unscaled the PCG needed more iterations than from 0
// (docs/ENGINE.md, "Design notes").
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "drape/newton/linear_solve.h"
#include "newton_test_matrices.h"

namespace drape::newton {
namespace {

struct Case {
  const char* name;
  bool fused, mixed;
};

double residual(const BlockMatrix& a, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  Eigen::VectorXd ax;
  a.multiply(x, ax);
  return (ax - b).norm();
}

TEST(NewtonWarmStart, AGuessPointingTheWrongWayIsTurnedRound) {
  const int n = 30;  // 900 block rows: several parallel chunks
  const auto pairs = shuffledGridCouplings(n, 11);
  // A grid Laplacian (times I3) with a small mass term: block-Jacobi PCG needs tens of iterations.
  BlockMatrix a(n * n, pairs, true);
  for (const auto& [i, j] : pairs) {
    a.addBlock(i, j, -Eigen::Matrix3d::Identity());
    a.addBlock(i, i, Eigen::Matrix3d::Identity());
    a.addBlock(j, j, Eigen::Matrix3d::Identity());
  }
  for (int i = 0; i < n * n; ++i) a.addBlock(i, i, 1e-2 * Eigen::Matrix3d::Identity());
  Eigen::VectorXd b(3 * n * n);
  for (Eigen::Index k = 0; k < b.size(); ++k) b(k) = std::cos(0.23 * (k + 1));
  for (const Case& c : {Case{"fused", true, false}, Case{"fused float", true, true}, Case{"plain", false, false}}) {
    LinearSolveOptions o;
    o.fusedKernels = c.fused;
    o.mixedPrecision = c.mixed;
    o.tolerance = 1e-8;
    o.warmStart = false;
    Eigen::VectorXd exact;
    ASSERT_TRUE(solveLinear(a, b, exact, o).ok);
    o.tolerance = 1e-2;
    Eigen::VectorXd cold;
    const int coldIterations = solveLinear(a, b, cold, o).iterations;
    ASSERT_GT(coldIterations, 20) << c.name;

    o.warmStart = true;
    // Minus the solution, slightly perturbed: the chattering garment's guess. Its best multiple is about -1.
    Eigen::VectorXd flipped = -exact;
    for (Eigen::Index k = 0; k < flipped.size(); k += 7) flipped(k) *= 0.9;
    Eigen::VectorXd x = flipped;
    const LinearSolveResult turned = solveLinear(a, b, x, o);
    ASSERT_TRUE(turned.ok) << c.name;
    EXPECT_LE(turned.iterations, coldIterations / 2) << c.name;
    EXPECT_LT(residual(a, x, b), 1.01e-2 * b.norm()) << c.name;

    // A guess far too long and nearly useless is no worse than 0.
    x = Eigen::VectorXd::Zero(b.size());
    x(5) = 1e3;
    const LinearSolveResult useless = solveLinear(a, b, x, o);
    EXPECT_LE(useless.iterations, coldIterations + 1) << c.name;
    EXPECT_LT(residual(a, x, b), 1.01e-2 * b.norm()) << c.name;

    // A good guess is taken as it is: a slightly scaled solution already meets the tolerance.
    x = 1.001 * exact;
    EXPECT_EQ(solveLinear(a, b, x, o).iterations, 0) << c.name;
    EXPECT_LT((x - 1.001 * exact).norm(), 1e-6 * exact.norm()) << c.name;
  }
}

}  // namespace
}  // namespace drape::newton
