// The quasi-Newton preview (the default preview): L-BFGS on the Newton drape's own incremental
// potential, its initial Hessian the PD-DD system (pd_preconditioner.h). Its converged step is Newton's step, the
// PD-DD preconditioner is the assembled system's inverse, it hands over to the drape without a restart and a cloth
// dropped hard on a sphere does not tunnel. That Newton's rest state is its rest state and that it settles every
// fabric preset at its long step are slow tests (tests/slow/quasi_newton_preview_drape_test.cpp).
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <memory>
#include <random>

#include "drape/collision/avatar_collider.h"
#include "drape/newton/newton_solver.h"
#include "drape/pd/pd_preconditioner.h"
#include "drape/pd/pd_system.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "newton_test_cloths.h"
#include "quasi_newton_preview_support.h"
#include "shared_data.h"

namespace drape::test {
namespace {

using drape::model::ClothModel;

// A hanging cloth with a stitch across it, so that the preconditioner has pins, stitches and fabric to hold.
ClothModel stitchedHangingCloth() {
  ClothModel m = newton::hangingGridCloth(9, 0.02, 7);
  m.stitches = {{10, 60}};
  return m;
}

TEST(PdPreconditioner, DecomposedAndMonolithicSolveTheAssembledSystem) {
  const ClothModel model = stitchedHangingCloth();
  const int n = model.numVertices();
  const double h = 1.0 / 120.0, stitch = 1e4, pin = 1e4;
  Eigen::VectorXd stiffness = Eigen::VectorXd::Zero(n);
  stiffness[5] = 1e3;
  stiffness[40] = 1e5;
  stiffness[model.pinned[0]] = 250.0;
  pd::PdPreconditioner dd(model, stitch, pin, 0.0, 0.0, 0.0, 3, pd::GlobalSolverKind::DomainDecomposed);
  pd::PdPreconditioner mono(model, stitch, pin, 0.0, 0.0, 0.0, 1, pd::GlobalSolverKind::Monolithic);
  ASSERT_TRUE(dd.prepare(h, 1.0, stiffness));
  ASSERT_TRUE(mono.prepare(h, 1.0, stiffness));

  // The system assembled here: PD's K over the free vertices plus the changing stiffness rounded as the
  // preconditioner rounds it (powers of 4: 1e3 -> 1024, 1e5 -> 65536); pinned vertices on the diagonal.
  pd::PreviewSettings settings;
  settings.timeStep = h;
  settings.shearModel = pd::ShearModelKind::Fabric;
  settings.stitchWeight = stitch;
  const pd::PdSystem system(model, settings);
  Eigen::SparseMatrix<double> k = system.matrix();
  const auto& dof = system.dofOfVertex();
  k.coeffRef(dof[5], dof[5]) += 1024.0;
  k.coeffRef(dof[40], dof[40]) += 65536.0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> direct(k);
  ASSERT_EQ(direct.info(), Eigen::Success);

  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  Eigen::VectorXd r(3 * n);
  for (Eigen::Index i = 0; i < r.size(); ++i) r[i] = normal(rng);
  Eigen::VectorXd a, b;
  dd.apply(r, a);
  mono.apply(r, b);
  EXPECT_LT((a - b).norm(), 1e-10 * b.norm());

  Eigen::MatrixX3d rhs(system.freeCount(), 3);
  for (int v = 0; v < n; ++v)
    if (dof[v] >= 0) rhs.row(dof[v]) = r.segment<3>(3 * v).transpose();
  const Eigen::MatrixXd expected = direct.solve(Eigen::MatrixXd(rhs));
  for (int v = 0; v < n; ++v) {
    if (dof[v] >= 0) {
      EXPECT_LT((a.segment<3>(3 * v) - expected.row(dof[v]).transpose()).norm(), 1e-9 * expected.norm()) << v;
    } else {
      const double diagonal = system.masses()[v] / (h * h) + pin + (v == model.pinned[0] ? 250.0 : 0.0);
      EXPECT_LT((a.segment<3>(3 * v) - r.segment<3>(3 * v) / diagonal).norm(), 1e-12) << v;
    }
  }
}

TEST(QuasiNewtonStep, ConvergedItIsNewtonsStep) {
  newton::NewtonSettings settings;
  settings.relaxation = false;
  settings.hMax = 1.0 / 120.0;
  settings.tauNewton = 1e-6;
  settings.maxNewtonIterations = 30;
  settings.linear.tolerance = 1e-10;
  settings.hessianReuseSteps = 0;
  const ClothModel model = stitchedHangingCloth();
  newton::NewtonSolver newton(model, settings);
  newton::NewtonSolver quasi(model, settings);
  auto preconditioner = std::make_shared<pd::PdPreconditioner>(model, settings.stitchStiffness, settings.pinStiffness,
                                                               settings.alpha, settings.betaStretch, settings.betaBend);
  newton::QuasiNewtonSettings qn;
  qn.maxIterations = 500;
  quasi.setQuasiNewton(preconditioner, qn);
  EXPECT_EQ(quasi.energyNames(), newton.energyNames());
  for (int step = 0; step < 3; ++step) {
    const newton::NewtonStepReport a = newton.step();
    const newton::NewtonStepReport b = quasi.step();
    ASSERT_EQ(a.status, newton::NewtonStatus::Converged);
    ASSERT_EQ(b.status, newton::NewtonStatus::Converged) << "residual " << b.residual;
    EXPECT_TRUE(b.quasiNewton);
    EXPECT_DOUBLE_EQ(a.h, b.h);
    const double moved = (newton.positions() - model.positions).norm();
    EXPECT_LT((quasi.positions() - newton.positions()).norm(), 1e-5 * moved) << "step " << step;
  }
}

TEST(QuasiNewtonPreview, SolvesTheDrapesTermsAndHandsOverWithoutARestart) {
  Simulation preview(defaultScene("full", {{"mesh.target_edge_length", "0.035"}}));
  Simulation drape(defaultScene("drape", {{"mesh.target_edge_length", "0.035"}}));
  EXPECT_EQ(preview.stage(), Stage::Preview);
  EXPECT_EQ(preview.terms(), drape.terms());
  const StepReport first = preview.step();
  EXPECT_TRUE(first.quasiNewton);
  EXPECT_EQ(first.stage, Stage::Preview);
  EXPECT_EQ(first.cgIterations, 0);
  EXPECT_GT(first.iterations, 0);
  EXPECT_NEAR(first.h, 1.0 / 480.0, 1e-12);  // the relaxation starts at a quarter of the preview's step
  while (preview.stage() == Stage::Preview) preview.step();
  // The hand-over keeps the positions and goes on at the preview's time with the same terms.
  const ResumeState handedOver = preview.resumeState();
  EXPECT_GT(handedOver.previewPositions.rows(), 0);
  EXPECT_LT((handedOver.previewPositions - preview.positions()).norm(), 1e-12);
  EXPECT_EQ(preview.terms(), drape.terms());
  const StepReport next = preview.step();
  EXPECT_EQ(next.stage, Stage::Drape);
  EXPECT_FALSE(next.quasiNewton);
  EXPECT_GT(next.time, handedOver.previewTime);
}

TEST(QuasiNewtonPreview, ClothDroppedHardOnASphereDoesNotTunnel) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "tablecloth.json";
  request.overrides = {{"solver.stage", "preview"},
                       {"sim.gravity", "-1000"},
                       {"solver.max_sim_time", "0.25"}};
  Simulation sim(loadScene(request));
  double lowest = 1e9;
  while (!sim.finished()) {
    ASSERT_NE(sim.step().status, StepStatus::Diverged);
    lowest = std::min(lowest, sim.positions().col(1).minCoeff());
  }
  const Eigen::MatrixX3d x = sim.positions();
  int inside = 0;
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    inside += sim.collider()->signedDistance(x.row(v).transpose()) < -sim.contactThickness();
  // At 1000 m/s^2 the cloth's free edges fall past the sphere's equator (y = 0.5 m) within the run.
  EXPECT_LT(lowest, 0.5);
  EXPECT_EQ(inside, 0);
}

}  // namespace
}  // namespace drape::test
