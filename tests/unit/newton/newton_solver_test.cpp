// Behaviour of the Backward-Euler Newton solver: quadratic convergence, hanging cloth equilibrium and symmetry,
// seams closing, time splitting, a first step below h_max, initial relaxation, divergence and cancellation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "drape/newton/newton_solver.h"
#include "drape/newton/springs.h"

using namespace drape::newton;

namespace {

// Cotton-like fabric of the brief.
drape::model::TriangleFabric cotton() {
  drape::model::TriangleFabric f;
  f.stretchWarp = f.stretchWeft = 5000.0;
  f.shear = 5000.0 / 20.0;
  f.bendWarp = f.bendWeft = 5e-6;
  f.density = 0.12;
  return f;
}

// Vertical panel of n x n vertices, side length `size`, in the x-y plane with its bottom-left corner at
// `origin`. Quad diagonals mirror about the middle column so the mesh is left-right symmetric.
void appendPanel(drape::model::ClothModel& m, int n, double size, const Eigen::Vector3d& origin) {
  const int base = m.numVertices();
  const double d = size / (n - 1);
  m.restCoords.conservativeResize(base + n * n, 2);
  m.positions.conservativeResize(3 * (base + n * n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.restCoords.row(base + i * n + j) << j * d, i * d;
      m.positions.segment<3>(3 * (base + i * n + j)) = origin + Eigen::Vector3d(j * d, i * d, 0.0);
    }
  int t = static_cast<int>(m.triangles.rows());
  m.triangles.conservativeResize(t + 2 * (n - 1) * (n - 1), 3);
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      int a = base + i * n + j, b = a + 1, c = a + n, e = c + 1;
      if (2 * j < n - 1) {
        m.triangles.row(t++) << a, b, e;
        m.triangles.row(t++) << a, e, c;
      } else {
        m.triangles.row(t++) << a, b, c;
        m.triangles.row(t++) << b, e, c;
      }
    }
}

drape::model::ClothModel hangingCloth(int n, double size) {
  drape::model::ClothModel m;
  m.fabrics = {cotton()};
  appendPanel(m, n, size, Eigen::Vector3d(0, 0, 0));
  m.pinned = {n * (n - 1), n * n - 1};  // top corners
  return m;
}

double maxEdgeStretch(const drape::model::ClothModel& m, const Eigen::VectorXd& x) {
  double worst = 0.0;
  for (int t = 0; t < m.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      int a = m.triangles(t, k), b = m.triangles(t, (k + 1) % 3);
      double rest = (m.restCoords.row(a) - m.restCoords.row(b)).norm();
      worst = std::max(worst, (x.segment<3>(3 * a) - x.segment<3>(3 * b)).norm() / rest);
    }
  return worst;
}

// An energy that turns NaN once armed (forces divergence).
class PoisonEnergy : public Energy {
 public:
  bool armed = false;
  std::string_view name() const override { return "poison"; }
  double value(const Eigen::VectorXd&) const override { return armed ? NAN : 0.0; }
  void addGradient(const Eigen::VectorXd&, Eigen::VectorXd& g) const override {
    if (armed) g(0) += NAN;
  }
  void addHessian(const Eigen::VectorXd&, BlockMatrix&) const override {}
};

}  // namespace

TEST(NewtonSolver, QuadraticConvergenceOnSmoothProblem) {
  drape::model::ClothModel m = hangingCloth(6, 0.2);
  for (int v = 0; v < m.numVertices(); ++v) m.positions(3 * v + 2) = 0.01 * std::sin(7.0 * v);  // out of plane
  NewtonSettings s;
  s.relaxation = false;
  s.alpha = s.betaStretch = s.betaBend = 0.0;
  s.projectHessians = false;  // exact Hessians: quadratic convergence expected
  s.hMax = 5e-3;
  s.tauNewton = 1e-13;
  s.maxNewtonIterations = 12;
  s.maxLineSearchIterations = 30;
  s.linear.kind = LinearSolverKind::Cholmod;
  NewtonSolver solver(m, s);
  NewtonStepReport r = solver.step();
  std::printf("residuals:");
  for (double x : r.residualHistory) std::printf(" %.3e", x);
  std::printf("\n");
  ASSERT_GE(r.residualHistory.size(), 4u);
  EXPECT_EQ(r.splits, 0);
  // Asymptotic regime: r_{k+1} <= C r_k^2 with a modest C over the last two contractions (linear convergence
  // with rate q would give r_{k+1} / r_k^2 = q / r_k, i.e. > 1e4 once r_k < 1e-5).
  const auto& h = r.residualHistory;
  EXPECT_LT(h.back(), 1e-12);
  int checked = 0;
  for (size_t k = h.size() - 1; k >= 1 && checked < 2; --k) {
    if (h[k - 1] > 1e-5) break;
    double c = h[k] / (h[k - 1] * h[k - 1]);
    std::printf("r_%zu / r_%zu^2 = %.1f\n", k, k - 1, c);
    EXPECT_LT(c, 2e3);
    ++checked;
  }
  EXPECT_EQ(checked, 2);
}

TEST(NewtonSolver, HangingClothReachesSymmetricEquilibrium) {
  const int n = 21;
  drape::model::ClothModel m = hangingCloth(n, 1.0);
  NewtonSolver solver(m, NewtonSettings{});
  EXPECT_EQ(solver.energyNames(), (std::vector<std::string>{"membrane", "bending", "pins", "gravity", "air_drag",
                                                            "stretch_damping", "bending_damping"}));
  NewtonStepReport r;
  int steps = 0;
  while (!solver.atRest() && solver.time() < 4.0) {
    r = solver.step();
    ASSERT_NE(r.status, NewtonStatus::Diverged) << "t = " << solver.time();
    ++steps;
  }
  std::printf("steps %d, t %.3f s, residual %.2e, KE99 %.2e, h %.2e\n", steps, solver.time(), r.residual,
              r.kineticPercentile, r.h);
  EXPECT_TRUE(solver.atRest());
  EXPECT_LT(r.residual, NewtonSettings{}.tauNewton);
  const Eigen::VectorXd& x = solver.positions();
  ASSERT_TRUE(x.allFinite());
  // The bottom has dropped under gravity, the corners stay pinned (springs: within 0.2 mm).
  EXPECT_LT(x(3 * (n / 2) + 1), -1e-3);
  EXPECT_LT((x.segment<3>(3 * m.pinned[0]) - m.positions.segment<3>(3 * m.pinned[0])).norm(), 2e-4);
  double asym = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      Eigen::Vector3d a = x.segment<3>(3 * (i * n + j)), b = x.segment<3>(3 * (i * n + n - 1 - j));
      asym = std::max(asym, std::abs(a.x() + b.x() - 1.0) + std::abs(a.y() - b.y()) + std::abs(a.z() - b.z()));
    }
  EXPECT_LT(asym, 1e-6);  // relative to the 1 m width
}

TEST(NewtonSolver, StitchedPanelsCloseTheSeam) {
  const int n = 6;
  drape::model::ClothModel m;
  m.fabrics = {cotton()};
  appendPanel(m, n, 0.2, Eigen::Vector3d(0, 0, 0));
  appendPanel(m, n, 0.2, Eigen::Vector3d(0.25, 0, 0));  // 5 cm gap
  for (int i = 0; i < n; ++i) m.stitches.emplace_back(i * n + n - 1, n * n + i * n);
  m.pinned = {n * (n - 1), n * n + n * n - 1};
  m.pinTargets = {Eigen::Vector3d(0, 0.2, 0), Eigen::Vector3d(0.4, 0.2, 0)};
  NewtonSolver solver(m, NewtonSettings{});
  StitchSprings probe(m.stitches, 1.0);
  EXPECT_NEAR(probe.maxGap(solver.positions()), 0.05, 1e-12);
  while (solver.time() < 0.5) ASSERT_NE(solver.step().status, NewtonStatus::Diverged);
  double gap = probe.maxGap(solver.positions());
  std::printf("seam gap after 0.5 s: %.3e m\n", gap);
  EXPECT_LT(gap, 1e-3);
  EXPECT_TRUE(solver.positions().allFinite());
}

TEST(NewtonSolver, TimeSplittingRecoversFromForcedFailure) {
  drape::model::ClothModel m = hangingCloth(8, 0.3);
  for (int v = 0; v < m.numVertices(); ++v) m.positions(3 * v) *= 1.3;  // stretched start
  NewtonSettings s;
  s.relaxation = false;
  s.maxNewtonIterations = 1;
  s.hMax = 0.05;  // 50x the paper's h_max
  s.tauNewton = 1e-5;
  NewtonSolver solver(m, s);
  NewtonStepReport r = solver.step();
  std::printf("splits %d, h %.3e, residual %.2e\n", r.splits, r.h, r.residual);
  EXPECT_EQ(r.status, NewtonStatus::Converged);
  EXPECT_GT(r.splits, 0);
  EXPECT_LT(r.h, 0.05);
  EXPECT_NEAR(r.h, 0.05 * std::pow(0.75, r.splits), 1e-15);
  for (int k = 0; k < 20; ++k) ASSERT_EQ(solver.step().status, NewtonStatus::Converged);
  EXPECT_TRUE(solver.positions().allFinite());
}

// NewtonSettings::startStep: the first step is startStep instead of h_max, and h grows back to h_max by the
// time-splitting rule (1 / omega after I_s good steps), as the drape that starts from the preview's state does.
TEST(NewtonSolver, StartStepGrowsToHMaxByTheSplittingRule) {
  NewtonSettings s;
  s.relaxation = false;
  s.hMax = 4e-3;
  s.startStep = 1e-3;
  NewtonSolver solver(hangingCloth(8, 0.3), s);
  double expected = s.startStep;
  int good = 0, stepsToHMax = -1;
  for (int k = 0; k < 40; ++k) {
    const NewtonStepReport r = solver.step();
    ASSERT_EQ(r.status, NewtonStatus::Converged);
    ASSERT_EQ(r.splits, 0);
    EXPECT_DOUBLE_EQ(r.h, expected) << "step " << k;
    if (r.h == s.hMax && stepsToHMax < 0) stepsToHMax = k;
    if (++good == s.growAfterSteps) {
      expected = std::min(s.hMax, expected / s.omega);
      good = 0;
    }
  }
  // 1 -> 4 ms takes five growths (the last one capped at h_max) of five steps each.
  EXPECT_EQ(stepsToHMax, 25);

  // A start step above h_max is capped; with the relaxation the smaller of it and h_max / 16 starts.
  s.startStep = 1.0;
  EXPECT_DOUBLE_EQ(NewtonSolver(hangingCloth(8, 0.3), s).step().h, s.hMax);
  s.relaxation = true;
  s.startStep = 1e-4;
  EXPECT_DOUBLE_EQ(NewtonSolver(hangingCloth(8, 0.3), s).step().h, 1e-4);
  s.startStep = 1e-3;
  EXPECT_DOUBLE_EQ(NewtonSolver(hangingCloth(8, 0.3), s).step().h, s.hMax / 16);
}

// Both relaxation step rules: "hold" keeps h_max / 16 for the whole 0.1 s window; "grow" (the default, the paper's
// initial time step) starts there and grows back by the time-splitting rule, still zeroing velocities and ramping
// the stiffness until 0.1 s.
TEST(NewtonSolver, RelaxationSettlesPreStretchedCloth) {
  for (bool hold : {true, false}) {
    SCOPED_TRACE(hold ? "hold" : "grow");
    drape::model::ClothModel m = hangingCloth(9, 0.3);
    m.pinned.clear();
    m.gravity.setZero();
    m.positions *= 2.0;  // 2x pre-stretch in both directions
    NewtonSettings s;
    s.relaxationHoldStep = hold;
    NewtonSolver solver(m, s);
    EXPECT_NEAR(maxEdgeStretch(m, solver.positions()), 2.0, 1e-12);
    int relaxingSteps = 0;
    double lastH = 0.0, relaxedTime = 0.0;
    while (solver.time() < 0.2) {
      NewtonStepReport r = solver.step();
      ASSERT_NE(r.status, NewtonStatus::Diverged);
      ASSERT_TRUE(solver.positions().allFinite() && solver.velocities().allFinite());
      if (r.relaxing) {
        if (relaxingSteps == 0) { EXPECT_EQ(r.h, s.hMax / 16); }
        ++relaxingSteps;
        relaxedTime = r.time;
        if (hold) { EXPECT_LE(r.h, s.hMax / 16 + 1e-18); }
        if (!hold && r.splits == 0) { EXPECT_GE(r.h, lastH); }  // grows back unless a step had to split
        EXPECT_EQ(solver.velocities().norm(), 0.0);
      }
      lastH = r.h;
    }
    double stretch = maxEdgeStretch(m, solver.positions());
    std::printf("%s: relaxing steps %d, max edge stretch after 0.2 s: %.4f\n", hold ? "hold" : "grow",
                relaxingSteps, stretch);
    EXPECT_GE(relaxedTime, 0.1 - s.hMax);  // the window lasts 0.1 s in both rules
    if (hold) { EXPECT_GE(relaxingSteps, 1000); }  // 0.1 s at h_max / 16
    if (!hold) {
      EXPECT_LT(relaxingSteps, 200);  // back at h_max after ~10 growths of 5 steps
      EXPECT_EQ(lastH, s.hMax);
    }
    EXPECT_LT(stretch, 1.05);
  }
}

// NewtonSettings::relaxationGuess: a relaxation step's Newton iterations start from the last step's velocity
// instead of from x_n. The step's equations are the same, so the relaxation ends at least as close to a tightly
// solved one as without the guess, in fewer Newton iterations: two hanging panels whose 10 cm seam gap the ramped
// stitches close during the 0.1 s window, as a garment's seams close in its relaxation.
TEST(NewtonSolver, RelaxationGuessNeedsFewerIterationsForTheSameSettling) {
  const int n = 8;
  drape::model::ClothModel m;
  m.fabrics = {cotton()};
  appendPanel(m, n, 0.2, Eigen::Vector3d(0, 0, 0));
  appendPanel(m, n, 0.2, Eigen::Vector3d(0.3, 0, 0));
  for (int i = 0; i < n; ++i) m.stitches.emplace_back(i * n + n - 1, n * n + i * n);
  m.pinned = {n * (n - 1), n * n + n * n - 1};
  auto relax = [&](bool guess, bool tight, int& iterations) {
    NewtonSettings s;
    s.relaxationGuess = guess;
    if (tight) {
      s.tauNewton = 1e-9;
      s.linear.tolerance = 1e-10;
      s.maxNewtonIterations = 20;
    }
    NewtonSolver solver(m, s);
    iterations = 0;
    while (solver.time() < s.relaxationTime - 1e-12) {
      const NewtonStepReport r = solver.step();
      EXPECT_EQ(r.status, NewtonStatus::Converged) << "t = " << r.time;
      EXPECT_TRUE(r.relaxing);
      iterations += r.newtonIterations;
    }
    return Eigen::VectorXd(solver.positions());
  };
  int refIterations = 0, offIterations = 0, onIterations = 0;
  const Eigen::VectorXd ref = relax(false, true, refIterations);
  const Eigen::VectorXd off = relax(false, false, offIterations);
  const Eigen::VectorXd on = relax(true, false, onIterations);
  const double moved = (ref - m.positions).norm();
  ASSERT_GT(moved, 0.05);
  const double offError = (off - ref).norm() / moved, onError = (on - ref).norm() / moved;
  std::printf(
      "relaxation: Newton iterations %d without the guess, %d with it (%d tightly solved); distance to the "
      "tight run / its motion: %.2e without, %.2e with\n",
      offIterations, onIterations, refIterations, offError, onError);
  EXPECT_LT(onIterations, 0.95 * offIterations);  // 3.3 -> 1.5 per step on the default scene's relaxation
  EXPECT_LT(onError, offError);
}

TEST(NewtonSolver, DivergenceKeepsLastGoodStateAndCancelStops) {
  drape::model::ClothModel m = hangingCloth(5, 0.2);
  std::vector<std::unique_ptr<Energy>> extra;
  auto poison = std::make_unique<PoisonEnergy>();
  PoisonEnergy* p = poison.get();
  extra.push_back(std::move(poison));
  NewtonSettings s;
  s.relaxation = false;
  s.hMin = 1e-5;
  NewtonSolver solver(m, s, std::move(extra));
  for (int k = 0; k < 3; ++k) ASSERT_EQ(solver.step().status, NewtonStatus::Converged);
  Eigen::VectorXd x = solver.positions(), v = solver.velocities();
  double t = solver.time();
  p->armed = true;
  NewtonStepReport r = solver.step();
  EXPECT_EQ(r.status, NewtonStatus::Diverged);
  EXPECT_GT(r.splits, 0);
  EXPECT_EQ(solver.positions(), x);
  EXPECT_EQ(solver.velocities(), v);
  EXPECT_EQ(solver.time(), t);
  p->armed = false;
  EXPECT_EQ(solver.step().status, NewtonStatus::Converged);
  solver.requestCancel();
  Eigen::VectorXd before = solver.positions();
  EXPECT_EQ(solver.step().status, NewtonStatus::Cancelled);
  EXPECT_EQ(solver.positions(), before);
}

// A step whose residual never gets below tau_n (here an unreachable 1e-30 with one Newton iteration) splits down
// to h_min and ends Diverged with the last good state kept, so that a caller stops instead of retrying it forever.
TEST(NewtonSolver, StepThatNeverConvergesEndsDivergedAtMinimumStep) {
  drape::model::ClothModel m = hangingCloth(5, 0.2);
  NewtonSettings s;
  s.relaxation = false;
  s.hMin = 1e-5;
  s.tauNewton = 1e-30;
  s.maxNewtonIterations = 1;
  NewtonSolver solver(m, s);
  const Eigen::VectorXd x = solver.positions(), v = solver.velocities();
  const NewtonStepReport r = solver.step();
  EXPECT_EQ(r.status, NewtonStatus::Diverged);
  EXPECT_GT(r.splits, 10);  // 1 ms down to 1e-5 s at omega 0.75
  EXPECT_EQ(solver.positions(), x);
  EXPECT_EQ(solver.velocities(), v);
  EXPECT_EQ(solver.time(), 0.0);
}

TEST(NewtonSolver, PreconditionersAndDirectSolveAgree) {
  drape::model::ClothModel m = hangingCloth(8, 0.3);
  Eigen::VectorXd reference;
  for (auto [kind, pre, mixed] :
       std::vector<std::tuple<LinearSolverKind, Preconditioner, bool>>{
           {LinearSolverKind::Cholmod, Preconditioner::None, false},
           {LinearSolverKind::Pcg, Preconditioner::None, false},
           {LinearSolverKind::Pcg, Preconditioner::Diagonal, false},
           {LinearSolverKind::Pcg, Preconditioner::BlockJacobi, false},
           {LinearSolverKind::Pcg, Preconditioner::IncompleteCholesky, false},
           {LinearSolverKind::Pcg, Preconditioner::BlockJacobi, true}}) {
    NewtonSettings s;
    s.relaxation = false;
    s.tauNewton = 1e-9;
    s.maxNewtonIterations = 20;
    s.linear.kind = kind;
    s.linear.preconditioner = pre;
    s.linear.mixedPrecision = mixed;
    s.linear.tolerance = 1e-5;
    NewtonSolver solver(m, s);
    for (int k = 0; k < 5; ++k) ASSERT_EQ(solver.step().status, NewtonStatus::Converged);
    if (reference.size() == 0)
      reference = solver.positions();
    else
      EXPECT_LT((solver.positions() - reference).norm(), 1e-6 * reference.norm()) << int(pre) << " " << mixed;
  }
}
