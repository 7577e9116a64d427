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

}  // namespace
}  // namespace drape::test
