// Coupled groups in the block-Jacobi preconditioner (coupled_groups.h): the groups are exactly the stiffly coupled
// vertices (a seam's stitched pairs and a three-panel corner), each group's block is the inverse of its submatrix
// (dynamic contact entries included), and the fused PCG with them meets its tolerance, agrees with CHOLMOD and
// needs fewer iterations on a stitched cloth at a long step; in the Newton solver they engage with the two-level
// PCG and leave the drape where it was.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <set>

#include "drape/newton/coupled_groups.h"
#include "drape/newton/linear_solve.h"
#include "drape/newton/newton_solver.h"
#include "newton_test_cloths.h"

using namespace drape::newton;

namespace {

// Two n x n panels side by side, each a membrane-like grid (springs of stiffness k along the rest directions,
// 1e-3 k across, plus mass m on the diagonal), joined by zero-length stitches of stiffness ks between panel A's
// right column and panel B's left column; the top stitch also takes a third vertex (a corner where three panels
// meet). Returns the stitched groups by vertex.
struct StitchedSystem {
  int n = 0;
  std::vector<std::pair<int, int>> couplings;
  std::vector<std::set<int>> groups;
};

StitchedSystem stitchedSystem(int n) {
  StitchedSystem s;
  s.n = n;
  for (int panel = 0; panel < 2; ++panel)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int a = panel * n * n + i * n + j;
        if (j + 1 < n) s.couplings.emplace_back(a, a + 1);
        if (i + 1 < n) s.couplings.emplace_back(a, a + n);
        if (i + 1 < n && j + 1 < n) s.couplings.emplace_back(a, a + n + 1);
      }
  const int extra = 2 * n * n;  // the third panel's corner vertex, joined to the top stitch
  for (int i = 0; i < n; ++i) {
    const int a = i * n + n - 1, b = n * n + i * n;
    s.couplings.emplace_back(a, b);
    if (i == n - 1) {
      s.couplings.emplace_back(a, extra);
      s.couplings.emplace_back(b, extra);
      s.groups.push_back({a, b, extra});
    } else {
      s.groups.push_back({a, b});
    }
  }
  return s;
}

void fillStitched(BlockMatrix& a, const StitchedSystem& s, double k, double ks, double m) {
  a.setZero();
  const int n = s.n;
  auto spring = [&a](int i, int j, const Eigen::Matrix3d& kb) {
    a.addBlock(i, j, -kb);
    a.addBlock(i, i, kb);
    a.addBlock(j, j, kb);
  };
  for (const auto& [i, j] : s.couplings) {
    const bool stitch = (i % (n * n)) % n == n - 1 && i < n * n && (j >= n * n);
    if (stitch) {
      spring(i, j, ks * Eigen::Matrix3d::Identity());
      continue;
    }
    const int li = i % (n * n), lj = j % (n * n);
    const Eigen::Vector3d d = Eigen::Vector3d(lj % n - li % n, lj / n - li / n, 0.0).normalized();
    spring(i, j, k * d * d.transpose() + 1e-3 * k * Eigen::Matrix3d::Identity());
  }
  for (int i = 0; i < a.numBlocks(); ++i) a.addBlock(i, i, m * Eigen::Matrix3d::Identity());
}

// The groups as sets of vertices (storage rows mapped back).
std::set<std::set<int>> groupsByVertex(const BlockMatrix& a, const CoupledGroups& g, std::vector<int>* rows = nullptr) {
  std::set<std::set<int>> out;
  // Probe apply() with unit residuals to recover the membership: a group's rows are the rows apply() writes.
  Eigen::VectorXd r = Eigen::VectorXd::Zero(a.size()), z = Eigen::VectorXd::Constant(a.size(), -7.0);
  for (Eigen::Index k = 0; k < r.size(); ++k) r(k) = 1.0 + 1e-3 * k;
  g.apply<double>(r, z);
  std::vector<int> written;
  for (int row = 0; row < a.numBlocks(); ++row)
    if (z(3 * row) != -7.0) written.push_back(row);
  if (rows) *rows = written;
  // Rows joined when their z depends on each other's r: perturb one row's r at a time.
  for (int row : written) {
    Eigen::VectorXd r2 = r;
    r2(3 * row) += 1.0;
    Eigen::VectorXd z2 = Eigen::VectorXd::Constant(a.size(), -7.0);
    g.apply<double>(r2, z2);
    std::set<int> group;
    for (int other : written)
      if ((z2.segment<3>(3 * other) - z.segment<3>(3 * other)).norm() > 1e-14) group.insert(a.originalIndex(other));
    out.insert(group);
  }
  return out;
}

}  // namespace

TEST(CoupledGroups, AreTheStitchedVerticesAndInvertTheirSubmatrices) {
  const int n = 12;
  const StitchedSystem s = stitchedSystem(n);
  BlockMatrix a(2 * n * n + 1, s.couplings, true);
  fillStitched(a, s, 100.0, 1e4, 1.0);
  // The corner's couplings are 1 / sqrt(2) of its diagonal blocks (its middle vertex holds two stitches).
  const CoupledGroups g(a, 0.6);
  ASSERT_EQ(g.count(), n);
  EXPECT_EQ(g.rows(), 2 * n + 1);
  const std::set<std::set<int>> expected(s.groups.begin(), s.groups.end());
  EXPECT_EQ(groupsByVertex(a, g), expected);

  // apply(): each group's z is its submatrix's inverse times its r (dense, from toSparse), other rows untouched,
  // and the returned change of r . z is exact.
  const Eigen::MatrixXd dense = Eigen::MatrixXd(a.toSparse());
  Eigen::VectorXd r(a.size()), z = Eigen::VectorXd::Constant(a.size(), 0.5);
  for (Eigen::Index k = 0; k < r.size(); ++k) r(k) = std::sin(0.37 * k + 0.1);
  const Eigen::VectorXd z0 = z;
  const double change = g.apply<double>(r, z);
  double expectedChange = 0.0;
  std::set<int> grouped;
  for (const std::set<int>& group : s.groups) {
    std::vector<int> v(group.begin(), group.end());
    const int m = static_cast<int>(v.size());
    Eigen::MatrixXd sub(3 * m, 3 * m);
    Eigen::VectorXd rg(3 * m), zg0(3 * m), zg(3 * m);
    for (int p = 0; p < m; ++p) {
      for (int q = 0; q < m; ++q) sub.block<3, 3>(3 * p, 3 * q) = dense.block<3, 3>(3 * v[p], 3 * v[q]);
      const int row = a.internalIndex(v[p]);
      rg.segment<3>(3 * p) = r.segment<3>(3 * row);
      zg0.segment<3>(3 * p) = z0.segment<3>(3 * row);
      zg.segment<3>(3 * p) = z.segment<3>(3 * row);
      grouped.insert(row);
    }
    const Eigen::VectorXd want = sub.ldlt().solve(rg);
    EXPECT_LT((zg - want).norm(), 1e-12 * want.norm());
    expectedChange += rg.dot(want) - rg.dot(zg0);
  }
  EXPECT_NEAR(change, expectedChange, 1e-12 * std::abs(expectedChange));
  for (int row = 0; row < a.numBlocks(); ++row)
    if (!grouped.count(row)) {
      EXPECT_EQ(z.segment<3>(3 * row), z0.segment<3>(3 * row)) << "row " << row;
    }
}

TEST(CoupledGroups, FollowTheThresholdTheSizeCapAndTheDynamicEntries) {
  const int n = 8;
  const StitchedSystem s = stitchedSystem(n);
  BlockMatrix a(2 * n * n + 1, s.couplings, true);
  // Stitches as stiff as the fabric at a short step: no coupling reaches the threshold (the stitches about 0.25,
  // the membrane springs less).
  fillStitched(a, s, 100.0, 100.0, 100.0);
  EXPECT_TRUE(CoupledGroups(a, 0.6).empty());
  // Stiff stitches, groups capped at two vertices: the corner's three cannot form one group, the pairs do.
  fillStitched(a, s, 100.0, 1e4, 1.0);
  EXPECT_EQ(CoupledGroups(a, 0.75).count(), n - 1) << "the corner's couplings are below 0.75";
  const CoupledGroups pairs(a, 0.6, 2);
  EXPECT_EQ(pairs.count(), n);
  for (const std::set<int>& group : groupsByVertex(a, pairs)) EXPECT_EQ(group.size(), 2u);

  // Dynamic entries (a contact on a stitched vertex, a cloth-cloth coupling inside the corner's group) enter the
  // group's submatrix on refresh(): apply() equals the dense solve of the whole matrix's submatrix.
  const int corner = 2 * n * n, top = n * n - 1;
  CoupledGroups g(a, 0.6);
  a.addDynamicBlock(top, top, 3e3 * Eigen::Matrix3d::Identity());
  Eigen::Matrix3d c;
  c << 10, 2, 0, 1, 10, 3, 0, 2, 10;
  a.addDynamicBlock(top, corner, -c);
  a.addDynamicBlock(top, top, c.transpose() * c / 10.0);
  a.addDynamicBlock(corner, corner, c.transpose() * c / 10.0);
  g.refresh(a);
  std::vector<int> v;
  for (const std::set<int>& group : s.groups)
    if (group.count(corner)) v.assign(group.begin(), group.end());
  ASSERT_EQ(v.size(), 3u);
  const Eigen::MatrixXd dense = Eigen::MatrixXd(a.toSparse());
  Eigen::MatrixXd sub(9, 9);
  Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(a.size(), -1.0, 2.0), z = Eigen::VectorXd::Zero(a.size());
  Eigen::VectorXd rg(9), zg(9);
  g.apply<double>(r, z);
  for (int p = 0; p < 3; ++p) {
    for (int q = 0; q < 3; ++q) sub.block<3, 3>(3 * p, 3 * q) = dense.block<3, 3>(3 * v[p], 3 * v[q]);
    rg.segment<3>(3 * p) = r.segment<3>(3 * a.internalIndex(v[p]));
    zg.segment<3>(3 * p) = z.segment<3>(3 * a.internalIndex(v[p]));
  }
  const Eigen::VectorXd want = sub.ldlt().solve(rg);
  EXPECT_LT((zg - want).norm(), 1e-12 * want.norm());
}

TEST(CoupledGroups, PcgWithThemMeetsTheToleranceInFewerIterations) {
  const int n = 40;  // 3201 block rows: several parallel chunks
  const StitchedSystem s = stitchedSystem(n);
  BlockMatrix a(2 * n * n + 1, s.couplings, true);
  fillStitched(a, s, 100.0, 1e4, 1.0);  // jersey-like membrane, 1e4 N/m stitches, mass term at a 10 ms step
  Eigen::VectorXd b(a.size());
  for (Eigen::Index k = 0; k < b.size(); ++k) b(k) = std::sin(0.013 * (k + 1)) + 0.1 * std::cos(0.7 * k);
  LinearSolveOptions direct;
  direct.kind = LinearSolverKind::Cholmod;
  Eigen::VectorXd exact;
  ASSERT_TRUE(solveLinear(a, b, exact, direct).ok);
  const CoupledGroups groups(a, 0.6);
  ASSERT_EQ(groups.count(), n);
  for (bool mixed : {false, true}) {
    LinearSolveOptions o;
    o.tolerance = mixed ? 1e-3 : 1e-6;  // a float PCG's true residual drifts from its recurrence below ~1e-4
    o.maxIterations = 5000;
    o.mixedPrecision = mixed;
    Eigen::VectorXd x1, x2;
    const LinearSolveResult alone = solveLinear(a, b, x1, o);
    o.coupled = &groups;
    const LinearSolveResult with = solveLinear(a, b, x2, o);
    ASSERT_TRUE(alone.ok && with.ok);
    std::printf("%s PCG: %d iterations with block-Jacobi alone, %d with the coupled groups (%.2fx)\n",
                mixed ? "mixed-precision" : "double", alone.iterations, with.iterations,
                static_cast<double>(alone.iterations) / with.iterations);
    EXPECT_LT(with.relativeResidual, mixed ? 2e-3 : 1.01e-6);
    EXPECT_LT((x2 - exact).norm(), (mixed ? 1e-2 : 1e-4) * exact.norm());
    EXPECT_LT(with.iterations, 0.7 * alone.iterations);
  }
}

// Two panels sewn along a seam, hanging from two corners, stepped at 10 ms (the drape after the preview): the
// coupled groups cut the PCG iterations, and the cloth ends where it ends without them (both runs solve each step
// to tau_n); by default they engage on solves that need many iterations.
TEST(CoupledGroups, EngageInTheNewtonSolverAndKeepItsResult) {
  const int n = 14;
  drape::model::ClothModel m;
  appendGridPanel(m, n, n, 0.3, 0.3, Eigen::Vector3d(0, 0, 0));
  appendGridPanel(m, n, n, 0.3, 0.3, Eigen::Vector3d(0.32, 0, 0));  // 2 cm gap, closed in the first steps
  drape::model::TriangleFabric f;
  f.stretchWarp = f.stretchWeft = 300.0;
  f.shear = 30.0;
  f.bendWarp = f.bendWeft = 1e-6;
  f.density = 0.15;
  m.fabrics = {f};
  for (int j = 0; j < n; ++j) m.stitches.emplace_back(j * n + n - 1, n * n + j * n);
  m.pinned = {n * (n - 1), 2 * n * n - 1};
  auto run = [&](double threshold, int& cg, int& coupledSolves, double h = 0.01, int from = 0) {
    NewtonSettings s;
    s.relaxation = false;
    s.hMax = h;
    s.coarseFromIterations = 0;  // the two-level PCG from the first solve
    s.coupledFromIterations = from;
    s.coupledThreshold = threshold;
    NewtonSolver solver(m, s);
    cg = coupledSolves = 0;
    while (solver.time() < 0.3 - 1e-9) {
      const NewtonStepReport r = solver.step();
      EXPECT_EQ(r.status, NewtonStatus::Converged) << "t = " << r.time;
      cg += r.cgIterations;
      coupledSolves += r.coupledSolves;
    }
    return Eigen::VectorXd(solver.positions());
  };
  int cgOff = 0, cgOn = 0, solvesOff = 0, solvesOn = 0;
  const Eigen::VectorXd off = run(0.0, cgOff, solvesOff), on = run(0.6, cgOn, solvesOn);
  const double moved = (off - m.positions).norm();
  std::printf(
      "30 steps of 10 ms: PCG iterations %d without the groups, %d with them (%d solves); positions %.2e "
      "apart relative to the motion\n",
      cgOff, cgOn, solvesOn, (on - off).norm() / moved);
  EXPECT_EQ(solvesOff, 0);
  EXPECT_GT(solvesOn, 0);
  EXPECT_LT(cgOn, 0.9 * cgOff);
  EXPECT_LT((on - off).norm(), 1e-3 * moved);
  // By default (coupledFromIterations 60) they wait for a solve that needs many iterations: at 10 ms the first
  // solves do, at 1 ms none does.
  int cg10 = 0, solves10 = 0, cg1 = 0, solves1 = 0;
  run(0.6, cg10, solves10, 0.01, NewtonSettings{}.coupledFromIterations);
  run(0.6, cg1, solves1, 0.001, NewtonSettings{}.coupledFromIterations);
  std::printf("default engagement: %d of the 10 ms steps' solves with the groups, %d of the 1 ms steps'\n", solves10,
              solves1);
  EXPECT_GT(solves10, 0);
  EXPECT_EQ(solves1, 0);
}
