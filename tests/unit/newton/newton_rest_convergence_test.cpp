// The Newton drape's rest-aware convergence (NewtonSettings::restAwareConvergence, docs/ENGINE.md `newton/`). Near
// rest, the paper's absolute tau_n (1e-3 kg m/s) accepts steps whose residual means velocity errors larger than the
// early stop's rest speed. In the A-line skirt's drape from the preview's state these errors kept about 1 % of the
// vertices creeping (at the back hem, beside the left leg), so the pipeline never came to rest. The rule itself, on a
// hanging cloth (0.1 s); the skirt's drape to rest is a slow test (tests/slow/newton_rest_convergence_skirt_test.cpp).
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <vector>

#include "drape/newton/newton_solver.h"
#include "newton_test_cloths.h"

namespace drape::test {
namespace {

// The rule itself on a hanging cloth (no contact): near rest a step below tau_n iterates on while its residual's
// velocity error is above the rest speed, and one that cannot get there is accepted at I_n, never split.
TEST(NewtonRestConvergence, NearRestStepsIterateOnButAreNeverSplit) {
  drape::model::ClothModel m = newton::gridCloth(12, 0.5 / 11, 0.0, 3);
  m.pinned = {12 * 11, 12 * 12 - 1};
  auto run = [&](bool restAware, double restSpeed, double restForce = 1e3) {
    newton::NewtonSettings s;
    s.relaxation = false;
    s.hessianReuseSteps = 0;
    s.restAwareConvergence = restAware;
    s.restSpeed = restSpeed;
    s.restForce = restForce;
    s.restAwareFactor = std::numeric_limits<double>::infinity();  // every step counts as near rest
    newton::NewtonSolver solver(m, s);
    std::vector<newton::NewtonStepReport> reports;
    for (int k = 0; k < 20; ++k) reports.push_back(solver.step());
    return reports;
  };
  for (const auto& r : run(false, 1e-300)) {  // the paper's test: one iteration reaches tau_n here
    EXPECT_EQ(r.newtonIterations, 1);
  }
  for (const auto& r : run(true, 1e3)) {  // a rest speed every velocity error is below: the same single iteration
    EXPECT_EQ(r.newtonIterations, 1);
  }
  int iterations = 0;
  for (const auto& r : run(true, 1e-300)) {  // a rest speed no velocity error reaches: more iterations, never a split
    EXPECT_EQ(r.status, newton::NewtonStatus::Converged) << "t = " << r.time;
    EXPECT_EQ(r.splits, 0) << "t = " << r.time;
    EXPECT_LT(r.residual, 1e-3);
    EXPECT_GE(r.newtonIterations, 2) << "t = " << r.time;
    EXPECT_LE(r.newtonIterations, 5);
    iterations += r.newtonIterations;
  }
  std::printf("[ NewtonRestConvergence ] unreachable threshold: %.2f Newton iterations per step\n", iterations / 20.0);
  // The same for the force the residual leaves (|b_i| / h against the vertex's weight): a rest speed every velocity
  // error is below, an unbalanced force none is.
  for (const auto& r : run(true, 1e3, 1e-300)) {
    EXPECT_EQ(r.splits, 0) << "t = " << r.time;
    EXPECT_GE(r.newtonIterations, 2) << "t = " << r.time;
  }
}

}  // namespace
}  // namespace drape::test
