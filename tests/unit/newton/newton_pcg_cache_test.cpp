// The fused PCG's kept preparation of an unchanged matrix (PcgCache): the same solves as a fresh preparation, read
// by the solve, and made again after the caller invalidates it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "drape/newton/linear_solve.h"
#include "newton_test_matrices.h"

namespace drape::newton {
namespace {

Eigen::VectorXd rightHandSide(int size, double phase) {
  Eigen::VectorXd b(size);
  for (Eigen::Index k = 0; k < b.size(); ++k) b(k) = std::sin(0.37 * (k + 1) + phase);
  return b;
}

TEST(NewtonPcgCache, KeptPreparationSolvesAsAFreshOne) {
  const int n = 30;  // 900 block rows: several parallel chunks
  const auto pairs = shuffledGridCouplings(n, 21);
  const Eigen::VectorXd b1 = rightHandSide(3 * n * n, 0.0), b2 = rightHandSide(3 * n * n, 1.3);
  for (bool mixed : {false, true}) {
    const std::string what = mixed ? "float" : "double";
    BlockMatrix a(n * n, pairs, true);
    fillSpd(a, pairs, 5);
    LinearSolveOptions o;
    o.mixedPrecision = mixed;
    o.tolerance = 1e-5;
    o.warmStart = false;
    Eigen::VectorXd fresh1, fresh2;
    ASSERT_TRUE(solveLinear(a, b1, fresh1, o).ok);
    ASSERT_TRUE(solveLinear(a, b2, fresh2, o).ok);

    PcgCache cache;
    o.cache = &cache;
    Eigen::VectorXd x1, x2;
    ASSERT_TRUE(solveLinear(a, b1, x1, o).ok);
    EXPECT_TRUE(cache.valid) << what;
    EXPECT_EQ(mixed ? cache.blocksFloat.size() : cache.inverse.size(), mixed ? a.blocks().size() : size_t(n * n));
    ASSERT_TRUE(solveLinear(a, b2, x2, o).ok);  // from the cache
    EXPECT_TRUE(x1 == fresh1) << what;
    EXPECT_TRUE(x2 == fresh2) << what;

    // The solve reads the kept data: a changed preconditioner block (still SPD) changes the iterates.
    if (mixed)
      cache.inverseFloat[7] *= 2.0f;
    else
      cache.inverse[7] *= 2.0;
    Eigen::VectorXd tampered;
    ASSERT_TRUE(solveLinear(a, b2, tampered, o).ok);
    EXPECT_FALSE(tampered == fresh2) << what;

    // A new matrix, invalidated: prepared again, the new matrix's solve.
    fillSpd(a, pairs, 6);
    cache.valid = false;
    Eigen::VectorXd again;
    ASSERT_TRUE(solveLinear(a, b2, again, o).ok);
    o.cache = nullptr;
    Eigen::VectorXd reference;
    ASSERT_TRUE(solveLinear(a, b2, reference, o).ok);
    EXPECT_TRUE(again == reference) << what;
    const Eigen::SparseMatrix<double> s = a.toSparse();
    EXPECT_LT((s * again - b2).norm(), (mixed ? 1e-4 : 1e-5) * b2.norm()) << what;
  }
}

}  // namespace
}  // namespace drape::newton
