// The production speed-ups of the Newton drape solver change nothing beyond round-off: closed-form hinge gradient
// against automatic differentiation, stencil colouring validity, assembly with the cached block map and coloured
// parallel loops against the plain serial search-based path, and whole solver runs with every switch on vs off.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "drape/newton/hinge_bending.h"
#include "drape/newton/newton_solver.h"
#include "drape/newton/stencil_set.h"
#include "drape/newton/strain_rate_damping.h"
#include "drape/newton/stvk_membrane.h"

using namespace drape::newton;

namespace {

// n x n grid of spacing d, anisotropic fabric, random 3D perturbation of amplitude `noise` * d.
ClothModel grid(int n, double d, double noise, unsigned seed) {
  ClothModel m;
  m.restCoords.resize(n * n, 2);
  m.positions.resize(3 * n * n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-noise * d, noise * d);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.restCoords.row(i * n + j) << j * d, i * d;
      m.positions.segment<3>(3 * (i * n + j)) << 1.05 * j * d + u(rng), i * d + u(rng), u(rng);
    }
  m.triangles.resize(2 * (n - 1) * (n - 1), 3);
  int t = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      int a = i * n + j, b = a + 1, c = a + n, e = c + 1;
      m.triangles.row(t++) << a, b, e;
      m.triangles.row(t++) << a, e, c;
    }
  TriangleFabric f;
  f.stretchWarp = 5000.0;
  f.stretchWeft = 3000.0;
  f.shear = 200.0;
  f.bendWarp = 5e-6;
  f.bendWeft = 2e-6;
  m.fabrics = {f};
  return m;
}

StepContext context(const Eigen::VectorXd& x0, const Eigen::VectorXd& v0, bool fast) {
  StepContext ctx{&x0, &v0, 1e-3, 0.0, 0.7, {}};
  ctx.assembly.closedFormBending = ctx.assembly.cachedBlockMap = ctx.assembly.parallel = fast;
  return ctx;
}

// Gradient and assembled Hessian of e at x, on a fresh matrix built from e's couplings.
std::pair<Eigen::VectorXd, Eigen::SparseMatrix<double>> derivatives(const Energy& e, const Eigen::VectorXd& x) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  e.addGradient(x, g);
  std::vector<std::pair<int, int>> pairs;
  e.addCouplings(pairs);
  BlockMatrix h(static_cast<int>(x.size() / 3), pairs);
  e.addHessian(x, h);
  e.addHessian(x, h);  // twice: the second pass reuses the cached slot map
  EXPECT_EQ(h.dynamicBlockCount(), 0) << e.name();
  Eigen::SparseMatrix<double> s = 0.5 * h.toSparse();
  return {g, s};
}

// Runs every assembly of e with the speed-ups off and on and compares.
void expectSameAssembly(Energy& e, const Eigen::VectorXd& x, const Eigen::VectorXd& x0, const Eigen::VectorXd& v0) {
  e.beginStep(context(x0, v0, false));
  auto [gSlow, hSlow] = derivatives(e, x);
  e.beginStep(context(x0, v0, true));
  auto [gFast, hFast] = derivatives(e, x);
  ASSERT_GT(gSlow.norm(), 0.0) << e.name();
  ASSERT_GT(hSlow.norm(), 0.0) << e.name();
  EXPECT_LT((gFast - gSlow).norm(), 1e-11 * gSlow.norm()) << e.name();
  EXPECT_LT((hFast - hSlow).norm(), 1e-11 * hSlow.norm()) << e.name();
}

}  // namespace

TEST(NewtonSpeedup, ClosedFormHingeGradientMatchesAutodiff) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ClothModel m = grid(2, 1.0, 0.0, 1);
  HingeBending bending(m);
  ASSERT_EQ(bending.hinges().size(), 1u);
  const Hinge h = bending.hinges()[0];
  int folded = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::VectorXd x = Eigen::VectorXd::NullaryExpr(12, [&] { return u(rng); });  // arbitrary angles
    Eigen::Matrix<double, 12, 1> ad = hingeAngleGradientAutodiff(h, x), cf = hingeAngleGradient(h, x);
    EXPECT_LT((cf - ad).norm(), 1e-9 * ad.norm()) << "trial " << trial;
    double theta = 0.0;
    hingeAngleGradient(h, x, true, theta);
    EXPECT_NEAR(theta, hingeAngle(h, x), 1e-14);
    if (std::abs(theta) > 2.0) ++folded;
  }
  EXPECT_GT(folded, 10);  // the sample covers sharp folds, not just near-flat hinges
}

TEST(NewtonSpeedup, ColouringSeparatesStencilsSharingAVertex) {
  ClothModel m = grid(15, 0.01, 0.1, 2);
  HingeBending bending(m);
  std::vector<std::array<int, 4>> hinges;
  for (const auto& h : bending.hinges()) hinges.push_back(h.v);
  StencilSet<4> set(hinges);
  std::vector<int> seen(hinges.size(), 0);
  for (int c = 0; c < set.numColours(); ++c) {
    std::set<int> vertices;
    for (int s : set.colour(c)) {
      ++seen[s];
      for (int v : set[s]) EXPECT_TRUE(vertices.insert(v).second) << "colour " << c << " shares vertex " << v;
    }
  }
  for (int count : seen) EXPECT_EQ(count, 1);
  EXPECT_GT(set.numColours(), 4);  // at least the 4 vertices of one hinge need distinct neighbours
  EXPECT_LT(set.numColours(), 40);
}

TEST(NewtonSpeedup, FastAssemblyEqualsSerialSearchAssembly) {
  ClothModel m = grid(30, 0.01, 0.3, 3);  // 841 vertices: colours large enough to run in parallel chunks
  Eigen::VectorXd x0 = grid(30, 0.01, 0.3, 4).positions, v0 = Eigen::VectorXd::Zero(x0.size());
  StvkMembrane membrane(m);
  expectSameAssembly(membrane, m.positions, x0, v0);
  HingeBending bending(m);
  expectSameAssembly(bending, m.positions, x0, v0);
  MembraneDissipation stretch(membrane.elements(), 1e-2);
  expectSameAssembly(stretch, m.positions, x0, v0);
  BendingDissipation bend(bending.hinges(), 1e-1);
  expectSameAssembly(bend, m.positions, x0, v0);
}

TEST(NewtonSpeedup, SolverResultsIndependentOfSwitches) {
  const int n = 12;
  ClothModel m = grid(n, 1.0 / (n - 1), 0.0, 5);
  m.pinned = {n * (n - 1), n * n - 1};
  Eigen::VectorXd reference;
  for (int config = 0; config < 2; ++config) {
    NewtonSettings s;
    s.relaxation = false;
    s.closedFormBending = s.cachedBlockMap = s.parallelAssembly = config == 1;
    NewtonSolver solver(m, s);
    for (int k = 0; k < 30; ++k) ASSERT_EQ(solver.step().status, NewtonStatus::Converged);
    ASSERT_GT((solver.positions() - m.positions).norm(), 1e-3);  // the cloth has moved
    if (config == 0)
      reference = solver.positions();
    else
      EXPECT_LT((solver.positions() - reference).norm(), 1e-8 * reference.norm());
  }
}
