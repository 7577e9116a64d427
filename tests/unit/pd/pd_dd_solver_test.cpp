// Domain-decomposed global solve (pd-dd section 4) against the monolithic CHOLMOD solve of the same K.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <tbb/task_arena.h>

#include "drape/pd/dd_solver.h"
#include "drape/pd/domain_partition.h"
#include "drape/pd/grid_cloth.h"
#include "drape/pd/pd_system.h"
#include "drape/pd/sparse_cholesky.h"
#include "drape/pd/subtree_groups.h"

namespace drape::pd {
namespace {

// Two panels meshed independently side by side, joined by stitches along their shared side, with pins.
drape::model::ClothModel twoPanelCloth() {
  GridClothOptions o;
  o.nx = 24;
  o.ny = 30;
  o.width = 0.5;
  o.height = 0.6;
  drape::model::ClothModel a = makeGridCloth(o);
  const int nv = a.numVertices();
  drape::model::ClothModel m = a;
  m.restCoords.conservativeResize(2 * nv, 2);
  m.positions.conservativeResize(6 * nv);
  m.triangles.conservativeResize(2 * a.triangles.rows(), 3);
  for (int v = 0; v < nv; ++v) {
    m.restCoords.row(nv + v) = a.restCoords.row(v);
    m.positions.segment<3>(3 * (nv + v)) = a.positions.segment<3>(3 * v) + Eigen::Vector3d(0.5, 0.0, 0.0);
  }
  for (int t = 0; t < a.triangles.rows(); ++t) m.triangles.row(a.triangles.rows() + t) = a.triangles.row(t).array() + nv;
  for (int j = 0; j < o.ny; ++j) m.stitches.emplace_back(j * o.nx + o.nx - 1, nv + j * o.nx);
  m.pinned = {(o.ny - 1) * o.nx, nv + o.ny * o.nx - 1, nv / 2};
  return m;
}

TEST(PdDdSolver, DomainMatricesSumToK) {
  const drape::model::ClothModel model = twoPanelCloth();
  PdSystem sys(model, PreviewSettings{});
  const int d = 8;
  const auto part = partitionTriangles(model.triangles, model.numVertices(), model.stitches, d);
  const auto domains = splitSystem(sys, part, d);
  Eigen::SparseMatrix<double> sum(sys.freeCount(), sys.freeCount());
  for (const auto& dm : domains) {
    std::vector<Eigen::Triplet<double>> t;
    for (int c = 0; c < dm.k.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(dm.k, c); it; ++it)
        t.emplace_back(dm.dofs[it.row()], dm.dofs[it.col()], it.value());
    Eigen::SparseMatrix<double> p(sys.freeCount(), sys.freeCount());
    p.setFromTriplets(t.begin(), t.end());
    sum += p;
  }
  const double diff = (Eigen::MatrixXd(sum) - Eigen::MatrixXd(sys.matrix())).norm();
  EXPECT_LT(diff, 1e-9 * Eigen::MatrixXd(sys.matrix()).norm());
  // Every domain is non-empty and holds a connected share of the triangles.
  std::vector<int> counts(d, 0);
  for (int p : part) ++counts[p];
  for (int c : counts) EXPECT_GT(c, 0);
}

TEST(PdDdSolver, EqualsMonolithicForManyDomainCounts) {
  const drape::model::ClothModel model = twoPanelCloth();
  PdSystem sys(model, PreviewSettings{});
  const int n = sys.freeCount();
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  Eigen::MatrixX3d b(n, 3);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) b(i, c) = normal(rng);
  MonolithicSolver mono(sys.matrix());
  ASSERT_TRUE(mono.ok());
  Eigen::MatrixX3d xm;
  mono.solve(b, xm);
  // Independent check of the reference: the residual of K x = b.
  EXPECT_LT((sys.matrix() * xm - b).norm() / b.norm(), 1e-10);
  for (int d : {1, 2, 4, 8, 16, 32}) {
    for (int stride : {0, 3}) {
      const auto part = partitionTriangles(model.triangles, model.numVertices(), model.stitches, d);
      DomainDecomposedSolver dd(splitSystem(sys, part, d), n, stride);
      ASSERT_TRUE(dd.ok()) << "D = " << d;
      Eigen::MatrixX3d x;
      dd.solve(b, x);
      const double rel = (x - xm).norm() / xm.norm();
      EXPECT_LT(rel, 1e-9) << "D = " << d << " stride " << stride;
      EXPECT_EQ(dd.domainCount(), d);
      if (d >= 4) {
        EXPECT_GT(dd.cornerCount(), 0) << "D = " << d;
        EXPECT_GT(dd.duplicateCount(), 0) << "D = " << d;
      }
      if (d == 1) {
        EXPECT_EQ(dd.cornerCount() + dd.duplicateCount(), 0);
      }
      // Class counts are consistent with the numbers reported.
      int corners = 0, dups = 0;
      for (DofClass c : dd.dofClasses()) {
        corners += c == DofClass::Corner;
        dups += c == DofClass::Duplicate;
      }
      EXPECT_EQ(corners, dd.cornerCount());
      EXPECT_EQ(dups, dd.duplicateCount());
    }
  }
}

// Largest entry error of the in-place solve of the first three columns of b against expected.
double inPlaceSolveError(const SparseCholesky& chol, const Eigen::MatrixXd& b, const Eigen::MatrixXd& expected) {
  const int n = static_cast<int>(b.rows());
  std::vector<double> x(3 * n), work(3 * n);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) x[3 * i + c] = b(i, c);
  chol.solveInPlace(x.data(), work.data());
  double err = 0.0;
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) err = std::max(err, std::abs(x[3 * i + c] - expected(i, c)));
  return err;
}

// The simplicial factor with our own three-column solves against Eigen's dense Cholesky of the same matrix.
TEST(PdSparseCholesky, SolvesLikeDenseCholeskyAndRejectsIndefinite) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  const int n = 300;
  std::vector<Eigen::Triplet<double>> trip;
  for (int i = 0; i < n; ++i) {
    trip.emplace_back(i, i, 4.0);
    for (int k = 0; k < 3; ++k) {  // random symmetric off-diagonals, diagonally dominant
      const int j = static_cast<int>(rng() % n);
      if (j == i) continue;
      const double v = 0.3 * uni(rng);
      trip.emplace_back(i, j, v);
      trip.emplace_back(j, i, v);
    }
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(trip.begin(), trip.end());
  SparseCholesky chol;
  ASSERT_TRUE(chol.factor(a));
  EXPECT_GE(chol.nonZeros(), n);
  Eigen::MatrixXd b(n, 5);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 5; ++c) b(i, c) = uni(rng);
  const Eigen::MatrixXd expected = Eigen::MatrixXd(a).llt().solve(b);
  EXPECT_LT((chol.solve(b) - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LT(inPlaceSolveError(chol, b, expected), 1e-12);  // the in-place three-column solve
  // Indefinite: a negative diagonal entry.
  Eigen::SparseMatrix<double> bad = a;
  bad.coeffRef(n / 2, n / 2) = -4.0;
  SparseCholesky badChol;
  EXPECT_FALSE(badChol.factor(bad));
  EXPECT_FALSE(badChol.ok());
}

// Groups of subtrees: on a balanced tree the root goes on top and each half forms a group; on a chain nothing
// splits; on random trees every node's parent is in its own group or on top, and top nodes have top parents.
TEST(PdSubtreeGroups, SplitsBalancedTreesAndKeepsDependenciesInsideGroups) {
  //      6
  //    2   5
  //   0 1 3 4
  const SubtreeGroups balanced = groupSubtrees({2, 2, 6, 5, 5, 6, -1}, std::vector<long>(7, 1), 2);
  ASSERT_EQ(balanced.groups.size(), 2u);
  EXPECT_EQ(balanced.top, std::vector<int>{6});
  EXPECT_EQ(balanced.cost, 4);
  std::vector<std::vector<int>> halves = balanced.groups;
  std::sort(halves.begin(), halves.end());
  EXPECT_EQ(halves[0], (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(halves[1], (std::vector<int>{3, 4, 5}));
  const SubtreeGroups chain = groupSubtrees({1, 2, 3, -1}, std::vector<long>(4, 1), 2);
  EXPECT_TRUE(chain.groups.empty());
  EXPECT_EQ(chain.cost, 4);

  std::mt19937 rng(3);
  int split = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 200;
    std::vector<int> parent(n);
    std::vector<long> cost(n);
    for (int j = 0; j < n; ++j) {
      parent[j] = j + 1 < n ? j + 1 + static_cast<int>(rng() % std::min(8, n - j - 1)) : -1;
      cost[j] = 1 + static_cast<long>(rng() % 50);
    }
    const SubtreeGroups g = groupSubtrees(parent, cost, 3);
    std::vector<int> groupOf(n, -2);
    for (int v : g.top) groupOf[v] = -1;
    for (size_t k = 0; k < g.groups.size(); ++k)
      for (int v : g.groups[k]) groupOf[v] = static_cast<int>(k);
    long total = 0, largest = 0, topCost = 0;
    for (long c : cost) total += c;
    for (int v : g.top) topCost += cost[v];
    for (const auto& grp : g.groups) {
      long sum = 0;
      for (int v : grp) sum += cost[v];
      largest = std::max(largest, sum);
    }
    for (int j = 0; j < n; ++j) {
      ASSERT_NE(groupOf[j], -2) << "node " << j << " in no group";
      if (parent[j] < 0) continue;
      if (groupOf[j] == -1) EXPECT_EQ(groupOf[parent[j]], -1) << "top node " << j << " below a group";
      else EXPECT_TRUE(groupOf[parent[j]] == groupOf[j] || groupOf[parent[j]] == -1) << "node " << j;
    }
    if (!g.groups.empty()) {
      ++split;
      EXPECT_EQ(g.cost, topCost + largest);
      EXPECT_LT(g.cost, total);
    }
  }
  EXPECT_GT(split, 10);
}

// A 30 x 30 grid cloth: its system matrix is a 2D mesh's, whose elimination tree splits.
GridClothOptions gridOptions30() {
  GridClothOptions o;
  o.nx = 30;
  o.ny = 30;
  return o;
}

// The subtree-parallel solve (groups of independent subtrees on several threads, then the separators above them)
// against Eigen's dense Cholesky, on the system matrix of a cloth (a 2D mesh, so the elimination tree splits), in
// an arena of 4 threads and one of 1 (no groups: the sequential solve).
TEST(PdSparseCholesky, SubtreeParallelSolveEqualsDenseCholesky) {
  const PdSystem sys(makeGridCloth(gridOptions30()), PreviewSettings{});
  const Eigen::SparseMatrix<double>& k = sys.matrix();
  const int n = static_cast<int>(k.rows());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Eigen::MatrixXd b(n, 3);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) b(i, c) = uni(rng);
  const Eigen::MatrixXd expected = Eigen::MatrixXd(k).llt().solve(b);
  for (int threads : {4, 1}) {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      SparseCholesky chol;
      ASSERT_TRUE(chol.factor(k, CholeskySolve::SubtreeParallel));
      if (threads > 1)
        EXPECT_GE(chol.subtreeGroups(), 2);
      else
        EXPECT_EQ(chol.subtreeGroups(), 0);
      for (int rep = 0; rep < 3; ++rep)  // repeated solves: no state left behind
        EXPECT_LT(inPlaceSolveError(chol, b, expected), 1e-10 * expected.cwiseAbs().maxCoeff()) << threads;
      EXPECT_LT((chol.solve(b) - expected).norm(), 1e-10 * expected.norm());
    });
  }
}

// The passes over the columns an interface reaches (the domain-decomposed solve's steps 1 and 4) against Eigen's
// dense Cholesky: the interface of a cloth's matrix is its border, as a domain's duplicates are. A right-hand side
// on the border solved forward over the reached columns, then backward in full, is the whole solve; the backward
// pass over the reached columns of a full forward result is exact on the border. The reached columns are fewer
// than all. (Without the ancestors of the border's columns the first solve is wrong: checked by mutation.)
TEST(PdSparseCholesky, PassesOverAnInterfaceEqualDenseCholeskyWhereTheyReach) {
  const GridClothOptions o = gridOptions30();
  const PdSystem sys(makeGridCloth(o), PreviewSettings{});
  const Eigen::SparseMatrix<double>& k = sys.matrix();
  const int n = static_cast<int>(k.rows());
  // The free DOFs on the grid's border (pins excluded by the system).
  std::vector<int> border;
  for (int d = 0; d < n; ++d) {
    const int v = sys.freeVertices()[d], i = v % o.nx, j = v / o.nx;
    if (i == 0 || j == 0 || i == o.nx - 1 || j == o.ny - 1) border.push_back(d);
  }
  ASSERT_GT(border.size(), 50u);
  SparseCholesky chol;
  ASSERT_TRUE(chol.factor(k));
  chol.setInterface(border);
  EXPECT_LT(chol.interfaceNonZeros(), chol.nonZeros());
  EXPECT_GE(static_cast<int>(chol.reachedColumns().size()), static_cast<int>(border.size()));
  const std::vector<int>& perm = chol.permutation();
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);

  // A right-hand side on the border only.
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n, 3);
  for (int d : border)
    for (int c = 0; c < 3; ++c) b(d, c) = uni(rng);
  Eigen::MatrixXd expected = Eigen::MatrixXd(k).llt().solve(b);
  std::vector<double> w(3 * n, 0.0);
  auto load = [&](const Eigen::MatrixXd& m) {
    for (int q = 0; q < n; ++q)
      for (int c = 0; c < 3; ++c) w[3 * q + c] = m(perm[q], c);
  };
  auto error = [&](const Eigen::MatrixXd& want, const std::vector<int>& rows) {
    std::vector<int> position(n);
    for (int q = 0; q < n; ++q) position[perm[q]] = q;
    double e = 0.0;
    for (int d : rows)
      for (int c = 0; c < 3; ++c) e = std::max(e, std::abs(w[3 * position[d] + c] - want(d, c)));
    return e / want.cwiseAbs().maxCoeff();
  };
  std::vector<int> all(n);
  for (int d = 0; d < n; ++d) all[d] = d;
  load(b);
  chol.forwardOverInterface(w.data());
  chol.backward(w.data());
  EXPECT_LT(error(expected, all), 1e-10);

  // A full right-hand side: forward in full, backward over the reached columns, exact on the border.
  for (int d = 0; d < n; ++d)
    for (int c = 0; c < 3; ++c) b(d, c) = uni(rng);
  expected = Eigen::MatrixXd(k).llt().solve(b);
  load(b);
  chol.forward(w.data());
  chol.backwardOverInterface(w.data());
  EXPECT_LT(error(expected, border), 1e-10);
  EXPECT_GT(error(expected, all), 1e-3);  // the columns it does not reach are left as the forward pass made them

}

TEST(PdSystemTest, HingeVectorVanishesOnAffineFields) {
  const Eigen::Vector2d r0(0, 0), r1(1.0, 0.1), r2(0.4, 0.8), r3(0.7, -0.9);
  const Eigen::Vector4d k = hingeVector(r0, r1, r2, r3);
  const Eigen::Vector2d rs[4] = {r0, r1, r2, r3};
  for (const Eigen::Vector3d& coef : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0.3, -2, 5)}) {
    double s = 0.0;
    for (int i = 0; i < 4; ++i) s += k[i] * (coef[0] + coef[1] * rs[i].x() + coef[2] * rs[i].y());
    EXPECT_NEAR(s, 0.0, 1e-12);
  }
  // A bent field (r3 lifted out of plane) is penalised.
  EXPECT_GT(std::abs(k[3]), 0.1);
}

TEST(PdSystemTest, StrainProjectionIsRotationForRigidMotionAndClampsStretch) {
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix<double, 3, 2> f = rot.leftCols<2>();
  const StrainProjection rigid = projectStrain(f, {}, {}, 0.0);
  EXPECT_LT((rigid.stretch - f).norm(), 1e-12);
  EXPECT_LT((rigid.shear - f).norm(), 1e-12);
  // Stretch 1.2 along the warp with limits [0.9, 1.1] comes back to 1.1; weft 0.95 stays within [0.9, 1.1]. The
  // shear projection leaves the (unsheared) stretch alone.
  Eigen::Matrix<double, 3, 2> g = f;
  g.col(0) *= 1.2;
  g.col(1) *= 0.95;
  const StrainProjection p = projectStrain(g, {0.9, 1.1}, {0.9, 1.1}, 0.0);
  EXPECT_NEAR(p.stretch.col(0).norm(), 1.1, 1e-12);
  EXPECT_NEAR(p.stretch.col(1).norm(), 0.95, 1e-12);
  EXPECT_NEAR(p.stretch.col(0).dot(p.stretch.col(1)), 0.0, 1e-12);
  EXPECT_LT((p.shear - g).norm(), 1e-12);
  // Collapsed triangle: still a finite orthonormal stretch target.
  const StrainProjection c = projectStrain(Eigen::Matrix<double, 3, 2>::Zero(), {}, {}, 0.0);
  EXPECT_NEAR((c.stretch.transpose() * c.stretch - Eigen::Matrix2d::Identity()).norm(), 0.0, 1e-12);
  EXPECT_TRUE(c.shear.allFinite());
}

// The polar rotation R of F = R S is defined by three properties: R^T R = I, S = R^T F symmetric and S positive
// definite. With both stretch limits [1, 1] and the shear held by the stretch, the stretch projection is R itself.
// Random F from round to thin (singular value ratio 5e-4) cover the closed-form square root of F^T F and, below
// a ratio of about 1e-3, the eigen decomposition; nearly collapsed F (1e-5 and less) get an orthonormal frame of
// the plane F spans.
TEST(PdSystemTest, StrainProjectionIsThePolarRotation) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  int checked = 0;
  for (double aspect : {1.0, 0.3, 1e-2, 1.5e-3, 1e-3, 5e-4, 1e-5, 1e-6, 1e-8})
    for (int k = 0; k < 50; ++k) {
      // F = Q[:, :2] Sigma U: singular values (scale, scale * aspect) in a random 3D frame and 2D rotation.
      const Eigen::Matrix3d q =
          Eigen::AngleAxisd(3.0 * normal(rng), Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized())
              .toRotationMatrix();
      const double angle = normal(rng), scale = std::exp(normal(rng));
      Eigen::Matrix2d u;
      u << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
      const Eigen::Matrix2d sigma = Eigen::Vector2d(scale, scale * aspect).asDiagonal();
      const Eigen::Matrix<double, 3, 2> f = q.leftCols<2>() * sigma * u;
      const StrainProjection p = projectStrain(f, {1.0, 1.0}, {1.0, 1.0}, 0.0, true);
      const Eigen::Matrix<double, 3, 2>& r = p.stretch;
      // Rounding in F^T F costs about eps / aspect^2 of the smaller singular value (in either method).
      const double tol = 1e-12 + 1e-15 / (aspect * aspect);
      const double orthonormality = aspect >= 5e-4 ? tol : 1e-12;
      EXPECT_LT((r.transpose() * r - Eigen::Matrix2d::Identity()).norm(), orthonormality) << "aspect " << aspect;
      if (aspect >= 5e-4) {
        const Eigen::Matrix2d s = r.transpose() * f;
        EXPECT_LT(std::abs(s(0, 1) - s(1, 0)), tol * scale) << "aspect " << aspect;
        EXPECT_GT(s.determinant(), 0.0) << "aspect " << aspect;
        EXPECT_GT(s.trace(), 0.0) << "aspect " << aspect;
        // The exact polar factor: F = (Q[:, :2] U) (U^T Sigma U).
        EXPECT_LT((r - q.leftCols<2>() * u).norm(), tol) << "aspect " << aspect;
      } else {
        EXPECT_LT((r * r.transpose() * f - f).norm(), 1e-6 * f.norm()) << "aspect " << aspect;
      }
      ++checked;
    }
  EXPECT_EQ(checked, 450);
}

}  // namespace
}  // namespace drape::pd
