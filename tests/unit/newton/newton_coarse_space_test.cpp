// The two-level PCG preconditioner (coarse_space.h): aggregates cover every row and are connected, the coarse solve
// equals an independent solve of P^T A P, and the two-level fused PCG meets its tolerance, agrees with CHOLMOD and
// needs fewer iterations than block-Jacobi alone on a stiff, cloth-like system.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <array>
#include <cstdio>
#include <queue>
#include <set>

#include "drape/newton/coarse_space.h"
#include "drape/newton/linear_solve.h"
#include "drape/newton/newton_solver.h"
#include "newton_test_cloths.h"

using namespace drape::newton;

namespace {

// Couplings of an n x n grid with diagonals (the triangle mesh of gridCloth) and its two-ring (the hinges).
std::vector<std::pair<int, int>> gridCouplings(int n) {
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j;
      if (j + 1 < n) pairs.emplace_back(a, a + 1);
      if (i + 1 < n) pairs.emplace_back(a, a + n);
      if (i + 1 < n && j + 1 < n) pairs.emplace_back(a, a + n + 1);
      if (i + 1 < n && j + 2 < n) pairs.emplace_back(a, a + n + 2);
    }
  return pairs;
}

// A stiff membrane-like system: 3D springs of stiffness k along every coupling (k d d^T with d the rest direction
// of a flat grid, so out-of-plane motion is soft) plus a mass term m on the diagonal: the stiffness to mass ratio
// of denim at h = 1 ms.
void fillCloth(BlockMatrix& a, int n, const std::vector<std::pair<int, int>>& pairs, double k, double m) {
  a.setZero();
  for (const auto& [i, j] : pairs) {
    const Eigen::Vector3d d = Eigen::Vector3d(j % n - i % n, j / n - i / n, 0.0).normalized();
    const Eigen::Matrix3d kb = k * d * d.transpose() + 1e-3 * k * Eigen::Matrix3d::Identity();
    a.addBlock(i, j, -kb);
    a.addBlock(i, i, kb);
    a.addBlock(j, j, kb);
  }
  for (int i = 0; i < n * n; ++i) a.addBlock(i, i, m * Eigen::Matrix3d::Identity());
}

// P in the original numbering: vertex v's three DOFs map to its aggregate's (through its storage row).
Eigen::SparseMatrix<double> prolongation(const BlockMatrix& a, const CoarseSpace& coarse) {
  std::vector<Eigen::Triplet<double>> t;
  for (int v = 0; v < a.numBlocks(); ++v)
    for (int d = 0; d < 3; ++d) t.emplace_back(3 * v + d, 3 * coarse.aggregateOfRow()[a.internalIndex(v)] + d, 1.0);
  Eigen::SparseMatrix<double> p(a.size(), 3 * coarse.numAggregates());
  p.setFromTriplets(t.begin(), t.end());
  return p;
}

// The coarse space's solve of a fixed right-hand side against an independent LDL^T solve of `galerkin`.
void expectCoarseSolveOf(const CoarseSpace& coarse, const Eigen::SparseMatrix<double>& galerkin) {
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(galerkin);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  Eigen::VectorXd rc(3 * coarse.numAggregates());
  for (Eigen::Index k = 0; k < rc.size(); ++k) rc(k) = std::sin(0.7 * k + 0.3);
  Eigen::VectorXd e;
  coarse.solve(rc, e);
  const Eigen::VectorXd expected = ldlt.solve(rc);
  EXPECT_LT((e - expected).norm(), 1e-10 * expected.norm());
}

// The same system solved by block-Jacobi PCG (o as given) and by the two-level PCG (o plus the coarse level).
struct PcgPair {
  LinearSolveResult blockJacobi, twoLevel;
  Eigen::VectorXd twoLevelSolution;
};
PcgPair solveOneAndTwoLevel(const BlockMatrix& a, const Eigen::VectorXd& b, const CoarseSpace& coarse,
                            LinearSolveOptions o) {
  PcgPair r;
  Eigen::VectorXd x1;
  r.blockJacobi = solveLinear(a, b, x1, o);
  o.coarse = &coarse;
  r.twoLevel = solveLinear(a, b, r.twoLevelSolution, o);
  return r;
}

}  // namespace

TEST(CoarseSpace, AggregatesCoverEveryRowAndAreConnected) {
  const int n = 30, size = 16;
  const auto pairs = gridCouplings(n);
  BlockMatrix a(n * n, pairs, true);
  CoarseSpace coarse(a, size);
  const std::vector<int>& agg = coarse.aggregateOfRow();
  ASSERT_EQ(static_cast<int>(agg.size()), n * n);
  std::vector<std::vector<int>> members(coarse.numAggregates());
  for (int r = 0; r < n * n; ++r) {
    ASSERT_GE(agg[r], 0);
    ASSERT_LT(agg[r], coarse.numAggregates());
    members[agg[r]].push_back(r);
  }
  EXPECT_GE(coarse.numAggregates(), n * n / size);
  EXPECT_LE(coarse.numAggregates(), n * n / 4) << "most aggregates should be near full size";
  for (const auto& m : members) {
    ASSERT_FALSE(m.empty());
    EXPECT_LE(static_cast<int>(m.size()), size);
    // Connected through the static pattern (storage rows).
    std::set<int> in(m.begin(), m.end()), seen{m.front()};
    std::queue<int> q;
    q.push(m.front());
    while (!q.empty()) {
      const int r = q.front();
      q.pop();
      for (int k = a.rowStarts()[r]; k < a.rowStarts()[r + 1]; ++k) {
        const int c = a.colIndices()[k];
        if (in.count(c) && seen.insert(c).second) q.push(c);
      }
    }
    EXPECT_EQ(seen.size(), m.size());
  }
}

TEST(CoarseSpace, CoarseSolveEqualsAnIndependentGalerkinSolve) {
  const int n = 20;
  const auto pairs = gridCouplings(n);
  BlockMatrix a(n * n, pairs, true);
  fillCloth(a, n, pairs, 1e4, 30.0);
  CoarseSpace coarse(a, 8);
  ASSERT_TRUE(coarse.factorize(a));
  const Eigen::SparseMatrix<double> p = prolongation(a, coarse);
  expectCoarseSolveOf(coarse, p.transpose() * a.toSparse() * p);
  // New values, same pattern: refactorised.
  fillCloth(a, n, pairs, 2e4, 10.0);
  ASSERT_TRUE(coarse.factorize(a));
  expectCoarseSolveOf(coarse, p.transpose() * a.toSparse() * p);
}

TEST(CoarseSpace, TwoLevelPcgMeetsTheToleranceInFewerIterations) {
  const int n = 60;  // 3600 block rows: several parallel chunks
  const auto pairs = gridCouplings(n);
  Eigen::VectorXd b(3 * n * n);
  for (Eigen::Index k = 0; k < b.size(); ++k) b(k) = std::sin(0.013 * (k + 1)) + 0.1 * std::cos(0.7 * k);
  BlockMatrix a(n * n, pairs, true);
  fillCloth(a, n, pairs, 1e4, 30.0);
  const Eigen::SparseMatrix<double> s = a.toSparse();
  LinearSolveOptions direct;
  direct.kind = LinearSolverKind::Cholmod;
  Eigen::VectorXd exact;
  ASSERT_TRUE(solveLinear(a, b, exact, direct).ok);
  CoarseSpace coarse(a, 16);
  ASSERT_TRUE(coarse.factorize(a));
  for (bool mixed : {false, true}) {
    LinearSolveOptions o;
    o.mixedPrecision = mixed;
    o.tolerance = mixed ? 1e-5 : 1e-8;
    o.maxIterations = 5000;
    const PcgPair pcg = solveOneAndTwoLevel(a, b, coarse, o);
    const LinearSolveResult& one = pcg.blockJacobi;
    const LinearSolveResult& two = pcg.twoLevel;
    const Eigen::VectorXd& x2 = pcg.twoLevelSolution;
    ASSERT_TRUE(one.ok && two.ok);
    const double trueResidual = (s * x2 - b).norm() / b.norm();
    EXPECT_LT(trueResidual, mixed ? 2e-5 : 1e-8);
    EXPECT_LT((x2 - exact).norm(), (mixed ? 1e-3 : 1e-6) * exact.norm());
    EXPECT_LT(two.iterations, one.iterations / 2) << "block-Jacobi " << one.iterations;
    std::printf("%s: block-Jacobi %d PCG iterations, two-level %d (%.1fx fewer)\n", mixed ? "float" : "double",
                one.iterations, two.iterations, double(one.iterations) / two.iterations);
  }
}

// The solver engages the coarse level after a solve that needed many block-Jacobi iterations (a stiff cloth), not
// on a soft one, and not when it is switched off.
TEST(CoarseSpace, SolverEngagesTheCoarseLevelOnlyWhereSolvesAreLong) {
  const int n = 30;
  auto coarseSolves = [&](double stiffness, int aggregate, int from) {
    drape::model::ClothModel m = hangingGridCloth(n, 0.0, 3);
    for (auto& f : m.fabrics) f.stretchWarp = f.stretchWeft = f.shear = stiffness;
    NewtonSettings s;
    s.relaxation = false;
    s.coarseAggregate = aggregate;
    s.coarseFromIterations = from;
    NewtonSolver solver(m, s);
    int used = 0, cg = 0;
    for (int k = 0; k < 20; ++k) {
      const NewtonStepReport r = solver.step();
      EXPECT_EQ(r.status, NewtonStatus::Converged);
      used += r.coarseSolves;
      cg += r.cgIterations;
    }
    std::printf("stretch stiffness %g N/m, aggregate %d, from %d: %d two-level solves, %d PCG iterations\n", stiffness,
                aggregate, from, used, cg);
    return used;
  };
  EXPECT_GT(coarseSolves(1e5, 16, 30), 10) << "stiff: long solves";
  EXPECT_EQ(coarseSolves(1e5, 0, 30), 0) << "switched off";
  EXPECT_EQ(coarseSolves(10.0, 16, 30), 0) << "soft: short solves";
  EXPECT_EQ(coarseSolves(1e5, 16, 100000), 0) << "threshold never reached";
  EXPECT_GE(coarseSolves(10.0, 16, 0), 20) << "threshold 0: every solve, from the first";
}

// Self-contact (cloth folded onto itself) adds dynamic blocks between vertices that are far apart on the cloth, in
// aggregates the static pattern does not join. The coarse matrix keeps only what falls on joined aggregates (the
// header): it must equal the Galerkin product of that part, stay positive definite, and the two-level PCG must still
// converge to the direct solve of the whole system.
TEST(CoarseSpace, SelfContactBetweenDistantAggregatesKeepsTheTwoLevelPcgExact) {
  const int n = 40;
  const auto pairs = gridCouplings(n);
  BlockMatrix a(n * n, pairs, true);
  fillCloth(a, n, pairs, 1e4, 30.0);
  // The grid folded along its middle row: vertex (i, j) of the lower half touches the triangle (i', j), (i', j + 1),
  // (i' - 1, j) of the mirrored row i' = n - 1 - i, as the vertex-triangle contacts of self_contact.cpp (penalty
  // Hessian k (w n)(w n)^T with w = (1, -b0, -b1, -b2), one call per unordered pair of stencil slots).
  const Eigen::Vector3d normal(0.0, 0.0, 1.0);
  const double k = 5e3;
  int contacts = 0;
  for (int i = 1; i < n / 2 - 1; i += 2)
    for (int j = 0; j + 1 < n; j += 3) {
      const int mirrored = n - 1 - i;
      const std::array<int, 4> v = {i * n + j, mirrored * n + j, mirrored * n + j + 1, (mirrored - 1) * n + j};
      const std::array<double, 4> w = {1.0, -0.5, -0.3, -0.2};
      for (int s = 0; s < 4; ++s)
        for (int t = s; t < 4; ++t) {
          const Eigen::Matrix3d b = k * w[s] * w[t] * normal * normal.transpose();
          if (v[s] == v[t])
            a.addDynamicBlock(v[s], v[s], s == t ? b : Eigen::Matrix3d(b + b.transpose()));
          else
            a.addDynamicBlock(v[s], v[t], b);
        }
      ++contacts;
    }
  CoarseSpace coarse(a, 16);
  const std::vector<int>& aggregate = coarse.aggregateOfRow();
  auto aggregateOf = [&](int vertex) { return aggregate[a.internalIndex(vertex)]; };
  // Aggregate pairs the static pattern joins, found independently of the coarse space's own bookkeeping.
  std::set<std::pair<int, int>> joined;
  for (int r = 0; r < a.numBlocks(); ++r)
    for (int q = a.rowStart(r); q < a.rowStart(r + 1); ++q) joined.insert({aggregate[r], aggregate[a.colIndex(q)]});
  int distant = 0;
  for (const auto& e : a.dynamicEntries()) distant += !joined.count({aggregateOf(e.i), aggregateOf(e.j)});
  ASSERT_GT(distant, contacts) << "the contacts must couple aggregates the static pattern does not join";
  ASSERT_TRUE(coarse.factorize(a)) << "the coarse matrix must stay positive definite";

  // Independent coarse matrix: P^T (static + the dynamic blocks on joined aggregates) P.
  const Eigen::SparseMatrix<double> p = prolongation(a, coarse);
  BlockMatrix kept(n * n, pairs, true);
  kept.setStaticValues(a.blocks());
  for (const auto& e : a.dynamicEntries())
    if (joined.count({aggregateOf(e.i), aggregateOf(e.j)})) kept.addDynamicBlock(e.i, e.j, e.block);
  expectCoarseSolveOf(coarse, p.transpose() * kept.toSparse() * p);

  // The two-level PCG on the whole system (every contact block) against CHOLMOD.
  Eigen::VectorXd b(3 * n * n);
  for (Eigen::Index q = 0; q < b.size(); ++q) b(q) = std::sin(0.013 * (q + 1)) + 0.1 * std::cos(0.7 * q);
  LinearSolveOptions direct;
  direct.kind = LinearSolverKind::Cholmod;
  Eigen::VectorXd exact;
  ASSERT_TRUE(solveLinear(a, b, exact, direct).ok);
  const Eigen::SparseMatrix<double> s = a.toSparse();
  ASSERT_LT((s * exact - b).norm(), 1e-10 * b.norm());
  LinearSolveOptions o;
  o.tolerance = 1e-8;
  o.maxIterations = 5000;
  const PcgPair pcg = solveOneAndTwoLevel(a, b, coarse, o);
  const LinearSolveResult& one = pcg.blockJacobi;
  const LinearSolveResult& two = pcg.twoLevel;
  const Eigen::VectorXd& x2 = pcg.twoLevelSolution;
  ASSERT_TRUE(one.ok && two.ok);
  EXPECT_LT((s * x2 - b).norm(), 1e-8 * b.norm());
  EXPECT_LT((x2 - exact).norm(), 1e-6 * exact.norm());
  EXPECT_LT(two.iterations, one.iterations) << "block-Jacobi " << one.iterations;
  std::printf("%d self contacts (%d dynamic blocks between unjoined aggregates): block-Jacobi %d PCG iterations, "
              "two-level %d\n", contacts, distant, one.iterations, two.iterations);
}
