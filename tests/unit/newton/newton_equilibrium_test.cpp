// The drape's measure of equilibrium (NewtonStepReport::forceMax, forceRms, displacementMax): the unbalanced force on
// each vertex at the step's end, as a fraction of its weight, and how far the step moved a vertex. The solver derives
// the force from the step's momentum residual; here it is summed afresh from the energies' gradients at the new
// positions, on a cloth without dissipation or contact, whose energies depend on the positions alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "drape/newton/newton_solver.h"
#include "newton_test_cloths.h"

namespace drape::test {
namespace {

TEST(NewtonEquilibrium, ForceIsTheEnergiesUnbalancedForceAtTheStepsEnd) {
  drape::model::ClothModel m = newton::hangingGridCloth(9, 0.05, 7);
  newton::NewtonSettings s;
  s.relaxation = false;
  s.alpha = 0.0;
  s.betaStretch = 0.0;
  s.betaBend = 0.0;
  newton::NewtonSolver solver(m, s);
  const double g = m.gravity.norm();
  ASSERT_GT(g, 0.0);
  for (int k = 0; k < 15; ++k) {
    const Eigen::VectorXd before = solver.positions();
    const newton::NewtonStepReport r = solver.step();
    ASSERT_EQ(r.status, newton::NewtonStatus::Converged);
    const Eigen::VectorXd& x = solver.positions();
    Eigen::VectorXd grad = Eigen::VectorXd::Zero(x.size());
    for (const auto& e : solver.energies()) e->addGradient(x, grad);
    double largest = 0.0, squares = 0.0, moved = 0.0;
    int count = 0;
    for (int i = 0; i < m.numVertices(); ++i) {
      moved = std::max(moved, (x.segment<3>(3 * i) - before.segment<3>(3 * i)).norm());
      const double mass = solver.masses()(i);
      if (mass <= 0.0) continue;
      const double fraction = grad.segment<3>(3 * i).norm() / (mass * g);
      largest = std::max(largest, fraction);
      squares += fraction * fraction;
      ++count;
    }
    const double rms = std::sqrt(squares / count);
    EXPECT_NEAR(r.forceMax, largest, 1e-6 * largest + 1e-9) << "step " << k;
    EXPECT_NEAR(r.forceRms, rms, 1e-6 * rms + 1e-9) << "step " << k;
    EXPECT_DOUBLE_EQ(r.displacementMax, moved) << "step " << k;
    EXPECT_GT(r.forceRms, 0.0);
  }
}

// At rest means balanced: with the rest speed alone met, a garment whose forces are not balanced to rest_force is not
// at rest.
TEST(NewtonEquilibrium, AtRestOnlyOnceTheForcesBalance) {
  drape::model::ClothModel m = newton::hangingGridCloth(7, 0.0, 3);
  auto run = [&](double restForce) {
    newton::NewtonSettings s;
    s.relaxation = false;
    s.restSpeed = 1e3;  // every speed is below it
    s.earlyStopWindow = 0.01;
    s.restForce = restForce;
    newton::NewtonSolver solver(m, s);
    newton::NewtonStepReport r;
    for (int k = 0; k < 40 && !solver.atRest(); ++k) r = solver.step();
    return std::make_pair(solver.atRest(), r);
  };
  const auto [loose, looseReport] = run(1e3);
  EXPECT_TRUE(loose);
  EXPECT_GT(looseReport.forceRms, 1e-2) << "the cloth was released: it is far from balanced";
  const auto [strict, strictReport] = run(1e-2);
  EXPECT_FALSE(strict) << "at rest with an RMS unbalanced force of " << strictReport.forceRms << " of the weight";
}

}  // namespace
}  // namespace drape::test
