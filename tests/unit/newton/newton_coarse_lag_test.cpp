// The two-level PCG's lagged coarse factor (NewtonSettings::coarseLagged, solver.cg.coarse_lagged). With contact
// every solve's matrix is new; lagged, the coarse matrix is factorised only where the elastic Hessian is assembled
// afresh at a step's start or h changes. The coarse level only preconditions, so the drape must end where the
// refactorised one ends, within a fraction of what the PCG tolerance itself moves it, with fewer factorisations.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

struct LagRun {
  Eigen::MatrixX3d positions;
  int steps = 0, solves = 0, coarseSolves = 0, factorizations = 0, cgIterations = 0;
};

// The tablecloth falling onto its sphere, Newton alone, the coarse level on every solve, at the paper's 1 ms step
// limit (400 steps).
LagRun dropTablecloth(bool lagged, const std::string& cgTolerance) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "tablecloth.json";
  request.overrides = {{"mesh.target_edge_length", "0.1"},
                       {"solver.stage", "drape"},
                       {"solver.max_sim_time", "0.4"},
                       {"solver.newton.relaxation", "false"},
                       {"solver.cg.coarse_from_iterations", "0"},
                       {"solver.cg.tolerance", cgTolerance},
                       {"solver.cg.coarse_lagged", lagged ? "true" : "false"},
                       {"solver.cg.mixed_precision", "false"}};
  request.overrides.emplace_back("solver.newton.h_max", "1e-3");
  Simulation sim(loadScene(request));
  LagRun run;
  int contactSteps = 0;
  while (!sim.finished()) {
    const StepReport r = sim.step();
    EXPECT_NE(r.status, StepStatus::Diverged) << "t = " << sim.time();
    if (r.status == StepStatus::Diverged) break;
    ++run.steps;
    run.solves += r.iterations;
    run.coarseSolves += r.coarseSolves;
    run.factorizations += r.coarseFactorizations;
    run.cgIterations += r.cgIterations;
    contactSteps += r.contacts > 0;
  }
  EXPECT_GT(contactSteps, run.steps / 4) << "the cloth must reach the sphere";
  run.positions = sim.positions();
  return run;
}

TEST(NewtonCoarseLag, LaggedFactorEndsWhereTheRefactorisedOneEndsWithFewerFactorisations) {
  const LagRun ref = dropTablecloth(false, "1e-6");
  const LagRun fresh = dropTablecloth(false, "1e-2");
  const LagRun lagged = dropTablecloth(true, "1e-2");
  for (const LagRun* r : {&ref, &fresh, &lagged}) {
    ASSERT_TRUE(r->positions.allFinite());
    EXPECT_EQ(r->coarseSolves, r->solves) << "coarse_from_iterations 0: every solve is two-level";
  }
  // Refactorised: every solve's matrix holds new contact blocks, so every solve factorises.
  EXPECT_EQ(fresh.factorizations, fresh.solves);
  // Lagged: once per fresh elastic Hessian (at least every hessian_reuse_steps + 1 steps) or new h.
  EXPECT_LT(lagged.factorizations, fresh.factorizations / 2);
  EXPECT_GT(lagged.factorizations, 0);
  EXPECT_LE(lagged.cgIterations, 1.25 * fresh.cgIterations);
  // Where they end: the PCG tolerance alone (1e-2 against 1e-6) moves the fallen cloth by centimetres; lagging the
  // coarse factor must move it by much less than that.
  const double cgEffect = (fresh.positions - ref.positions).rowwise().norm().maxCoeff();
  const double lagEffect = (lagged.positions - fresh.positions).rowwise().norm().maxCoeff();
  std::printf(
      "steps %d; factorisations %d refactorised, %d lagged (%d solves); PCG iterations %d / %d; largest "
      "vertex distance: tolerance 1e-2 against 1e-6 %.2e m, lagged against refactorised %.2e m\n",
      fresh.steps, fresh.factorizations, lagged.factorizations, lagged.solves, fresh.cgIterations, lagged.cgIterations,
      cgEffect, lagEffect);
  EXPECT_LT(lagEffect, 0.25 * cgEffect);
}

}  // namespace
}  // namespace drape::test
