// Issue 5: a bending hinge whose wing triangle has collapsed (its opposite vertex on the hinge edge's line).
// The dihedral angle's gradient grows as 1 / (wing height) there: in the default T-shirt scene with tau_n = 1e-5
// a wing collapsed to 1e-9 m, its hinge pulled with 5e4 N, and time splitting drove h to h_min (t = 0.051 s).
// The bending measure now fades out on collapsing wings (hinge_bending.h); these tests pin that down.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "drape/newton/hinge_bending.h"
#include "energy_fd_check.h"
#include "newton_test_cloths.h"

using namespace drape::newton;

namespace {

struct Wing {
  Eigen::Vector3d foot;       // point of the edge line closest to x3
  Eigen::Vector3d direction;  // unit, from the foot towards x3
};

// Two triangles sharing one hinge, wing B folded by `fold` radians out of the flat state with its vertex x3 at
// signed distance `height` (metres) from the edge line; hinge receives the model's only hinge.
drape::model::ClothModel foldedHinge(double height, double fold, Hinge& hinge, Wing& wing) {
  drape::model::ClothModel m = gridCloth(2, 0.02, 0.0, 1);
  hinge = buildHinges(m).at(0);
  Eigen::VectorXd& x = m.positions;
  const Eigen::Vector3d x0 = x.segment<3>(3 * hinge.v[0]), x1 = x.segment<3>(3 * hinge.v[1]);
  const Eigen::Vector3d x2 = x.segment<3>(3 * hinge.v[2]);
  const Eigen::Vector3d e = (x1 - x0).normalized();
  Eigen::Vector3d awayA = (x2 - x0) - (x2 - x0).dot(e) * e;  // wing A's in-plane direction off the edge
  awayA.normalize();
  // Flat: wing B points opposite to wing A; folding rotates that direction about the edge.
  wing.foot = x0 + 0.4 * (x1 - x0);
  wing.direction = Eigen::AngleAxisd(fold, e) * (-awayA);
  x.segment<3>(3 * hinge.v[3]) = wing.foot + height * wing.direction;
  return m;
}

TEST(NewtonDegenerateHinge, BendingStaysFiniteOnACollapsedWing) {
  Hinge hinge;
  Wing wing;
  drape::model::ClothModel m = foldedHinge(1e-9, 2.4, hinge, wing);
  HingeBending bending(m);
  bending.beginStep(StepContext{});
  Eigen::VectorXd g = Eigen::VectorXd::Zero(m.positions.size());
  bending.addGradient(m.positions, g);
  ASSERT_TRUE(g.allFinite());
  // The same fold with an intact wing pulls with k |theta| |grad theta| of about 6e-3 N (without the fade this
  // collapsed wing pulled with 6e4 N); a collapsed wing must not pull harder than an intact one.
  EXPECT_LT(g.norm(), 1e-2);
}

// Inside the fade band (wing B at 10% of its rest area) the bending gradient and its exact Hessian match central
// differences, and the closed-form and automatic-differentiation gradients of phi agree.
TEST(NewtonDegenerateHinge, FadedBendingMatchesFiniteDifferences) {
  Hinge hinge;
  Wing wing;
  const double restHeight = 0.02 / std::sqrt(2.0);  // of the wing triangles across the grid square's diagonal
  drape::model::ClothModel m = foldedHinge(0.1 * 1.05 * restHeight, 2.4, hinge, wing);
  HingeBending e(m);
  e.setExactHessian(true);
  e.beginStep(StepContext{});
  const Eigen::VectorXd x = m.positions;
  double phi = 0.0, phiAd = 0.0;
  const Eigen::Matrix<double, 12, 1> cf = hingeBendGradient(hinge, x, true, phi);
  const Eigen::Matrix<double, 12, 1> ad = hingeBendGradient(hinge, x, false, phiAd);
  EXPECT_NEAR(phi, phiAd, 1e-14);
  EXPECT_GT(std::abs(phi), 0.01);
  EXPECT_LT(std::abs(phi), 0.9 * std::abs(hingeAngle(hinge, x)));  // faded
  EXPECT_LT((cf - ad).norm(), 1e-9 * ad.norm());
  checkEnergy(e, x, true, 1e-7);
}

}  // namespace
