// Lagged friction at a step's first Newton iterate (FrictionParameters::majorizeAtPrediction, friction.h). A cloth
// sliding on a flat floor must stop and stay: Backward Euler takes mu g h off its speed per step and then sticks
// it. With the Hessian at the predicted slip h v_n the step that should stop it overshoots and turns the slip round.
// Alone on the floor the line search would see that; beside motion elsewhere, as in a garment, the residual is
// dominated by the rest of the cloth, the overshoot's error (2 mu lambda h per vertex) is far below tau_n, the step
// is accepted, and the velocity turns round every step from then on. With the isotropic majorizer the slip shrinks
// into the static regime and the cloth stays put; in exchange a single iteration brakes a decelerating slip less
// than Backward Euler does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "drape/newton/contact/contact_factory.h"
#include "drape/geometry/primitives.h"
#include "drape/newton/newton_solver.h"
#include "newton_test_cloths.h"

namespace drape::newton {
namespace {

struct SlideResult {
  std::vector<double> meanVelocityX;  // m/s, per step
  double travel = 0.0;                // m, mean x displacement over the run
};

// One small triangle (2 cm legs) lying on the top face (y = 0) of a box, pressed into the contact layer by its
// weight, all three vertices sliding along x at 1.75 cm/s, mu = 0.5: Backward Euler takes mu g h = 4.9 mm/s off per
// step of 1 ms and stops it in the fourth. Beside the box, away from it, a 30 cm panel hangs from its two top
// corners and swings under gravity for the whole run.
SlideResult slide(bool majorizer, int steps) {
  const int n = 3;
  drape::model::ClothModel m;
  m.restCoords.resize(n, 2);
  m.restCoords << 0.0, 0.0, 0.02, 0.0, 0.0, 0.02;
  m.triangles.resize(1, 3);
  m.triangles << 0, 1, 2;
  m.fabrics = {drape::model::TriangleFabric{5000.0, 3000.0, 200.0, 5e-6, 2e-6}};  // gridCloth's fabric (the panel's too)
  const double thickness = 2e-3, stiffness = 100.0;
  const double vertexMass = m.fabrics[0].density * 0.5 * 0.02 * 0.02 / 3.0;
  m.positions.resize(3 * n);
  for (int i = 0; i < n; ++i) {  // flat (x-z plane), at the depth where the penalty carries the vertex's weight
    m.positions.segment<3>(3 * i) << m.restCoords(i, 0), thickness - vertexMass * 9.81 / stiffness,
        m.restCoords(i, 1);
  }
  const int panel = 10;
  appendGridPanel(m, panel, panel, 0.3, 0.3, Eigen::Vector3d(2.0, 0.5, 0.0));
  m.pinned = {n + panel * (panel - 1), n + panel * panel - 1};
  m.velocities = Eigen::VectorXd::Zero(m.positions.size());
  for (int i = 0; i < n; ++i) m.velocities(3 * i) = 0.0175;
  newton::ContactSetup setup;
  setup.avatar = std::make_shared<collision::AvatarCollider>(
      makeBox(Eigen::Vector3d(-1.0, -1.0, -1.0), Eigen::Vector3d(1.0, 0.0, 1.0)));
  setup.avatarContact.thickness = thickness;
  setup.avatarContact.stiffness = stiffness;
  setup.frictionCoefficient = 0.5;
  setup.frictionMajorizer = majorizer;
  const Eigen::VectorXd start = m.positions;
  NewtonSettings s;
  s.relaxation = false;
  // Only tau_n decides, as in a garment still falling elsewhere: near rest the equilibrium test (restForce) iterates
  // on while the residual leaves an unbalanced force, which would resolve the overshoot here too.
  s.restForce = 1e3;
  NewtonSolver solver(m, s, newton::makeContactEnergies(setup, m.numVertices(), m.triangles, {}));
  SlideResult out;
  for (int k = 0; k < steps; ++k) {
    const NewtonStepReport r = solver.step();
    EXPECT_EQ(r.status, NewtonStatus::Converged) << "step " << k;
    double vx = 0.0;
    for (int i = 0; i < n; ++i) vx += solver.velocities()(3 * i);
    out.meanVelocityX.push_back(vx / n);
  }
  for (int i = 0; i < n; ++i) out.travel += (solver.positions()(3 * i) - start(3 * i)) / n;
  return out;
}

int signChanges(const std::vector<double>& v, size_t from) {
  int changes = 0;
  for (size_t k = from + 1; k < v.size(); ++k) changes += (v[k] > 0.0) != (v[k - 1] > 0.0);
  return changes;
}

TEST(NewtonFrictionStick, MajorizerLetsASlidingClothStickWhereTheHessianChatters) {
  const int steps = 40;
  const SlideResult hessian = slide(false, steps);
  const SlideResult majorizer = slide(true, steps);
  // Backward Euler solved exactly: v drops by mu g h per step until it would change sign, then sticks.
  const double h = 1e-3, v0 = 0.0175, brake = 0.5 * 9.81 * h;
  double exactTravel = 0.0;
  for (double v = v0 - brake; v > 0.0; v -= brake) exactTravel += h * v;
  std::printf("[ NewtonFrictionStick ] travel: majorizer %.1f um, Hessian %.1f um, Backward Euler %.1f um; first "
              "step's braking %.2f / %.2f mm/s (exact %.2f); last |v| %.1e / %.1e m/s; sign changes over the last 30 "
              "steps: %d / %d\n",
              1e6 * majorizer.travel, 1e6 * hessian.travel, 1e6 * exactTravel, 1e3 * (v0 - majorizer.meanVelocityX[0]),
              1e3 * (v0 - hessian.meanVelocityX[0]), 1e3 * brake, std::abs(majorizer.meanVelocityX.back()),
              std::abs(hessian.meanVelocityX.back()), signChanges(majorizer.meanVelocityX, 10),
              signChanges(hessian.meanVelocityX, 10));
  // The Hessian's single iteration is Backward Euler's step while sliding ...
  EXPECT_NEAR(hessian.meanVelocityX[0], v0 - brake, 2e-4);
  // ... but the step that should stop the cloth turns it round, and so does every step after it.
  EXPECT_GE(signChanges(hessian.meanVelocityX, 10), 25);
  EXPECT_GT(std::abs(hessian.meanVelocityX.back()), 1e-3);
  // The majorizer brakes a decelerating slip less in one iteration (the price: it stops later and slides further),
  // never turns it round, and the cloth stays stuck, far below the static regime's slip velocity (epsV = 1 mm/s).
  EXPECT_GT(majorizer.meanVelocityX[0], v0 - brake + 2e-4);
  EXPECT_LT(majorizer.meanVelocityX[0], v0 - 0.5 * brake);
  for (int k = 0; k < steps; ++k) EXPECT_GT(majorizer.meanVelocityX[k], -1e-5) << "step " << k;
  for (int k = 10; k < steps; ++k) EXPECT_LT(std::abs(majorizer.meanVelocityX[k]), 1e-5) << "step " << k;
  EXPECT_GT(majorizer.travel, exactTravel);
  EXPECT_LT(majorizer.travel, 2.0 * exactTravel);
}

}  // namespace
}  // namespace drape::newton
