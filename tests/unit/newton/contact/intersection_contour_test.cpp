// Untangling by the intersection contour (newton/contact/intersection_contour.h): the crossing segment of two
// triangles against hand-computed cuts, its gradient against central differences, and a panel pushed through
// another that comes back out once released, where the self-contact penalty alone would hold it through; the pull
// held over a Newton step against the followed contour's gradient.
#include "drape/newton/contact/intersection_contour.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "drape/collision/self_intersection.h"
#include "drape/newton/contact/contact_factory.h"
#include "drape/newton/newton_solver.h"
#include "newton_test_cloths.h"

namespace drape {
namespace {

using Eigen::Vector3d;
using newton::crossingLength;

// Triangle A in the plane z = 0, legs 1 m along x and y.
const Vector3d a0(0, 0, 0), a1(1, 0, 0), a2(0, 1, 0);

TEST(IntersectionContour, CrossingLengthIsTheCutOfTheOtherTriangle) {
  // B upright in the plane y = 0.2 from z = -0.5 to 0.5: its edges b0-b1 and b0-b2 cross z = 0 halfway, at
  // x = 0.3 and x = 0.15, both inside A.
  const Vector3d b0(0.1, 0.2, -0.5), b1(0.5, 0.2, 0.5), b2(0.2, 0.2, 0.5);
  EXPECT_NEAR(crossingLength(a0, a1, a2, b0, b1, b2), 0.15, 1e-12);
  EXPECT_NEAR(crossingLength(b0, b1, b2, a0, a1, a2), 0.15, 1e-12);
}

TEST(IntersectionContour, CrossingLengthEndsAtTheFirstTrianglesEdge) {
  // B's cut runs from x = 0.6 to 0.9 at y = 0.2, but A ends at x + y = 1, x = 0.8 there: A's hypotenuse pierces B.
  const Vector3d b0(0.6, 0.2, -0.5), b1(1.2, 0.2, 0.5), b2(0.6, 0.2, 0.5);
  EXPECT_NEAR(crossingLength(a0, a1, a2, b0, b1, b2), 0.2, 1e-12);
}

TEST(IntersectionContour, TrianglesThatDoNotCrossHaveNoLengthAndNoGradient) {
  // Above A, and beside it (cut line outside A).
  const Vector3d up(0, 0, 0.1);
  Eigen::Matrix<double, 18, 1> g;
  EXPECT_EQ(crossingLength(a0, a1, a2, a0 + up, a1 + up, a2 + up, &g), 0.0);
  EXPECT_EQ(g.norm(), 0.0);
  EXPECT_EQ(crossingLength(a0, a1, a2, Vector3d(2, 2, -1), Vector3d(3, 2, 1), Vector3d(2, 3, 1), &g), 0.0);
  EXPECT_EQ(g.norm(), 0.0);
}

TEST(IntersectionContour, GradientMatchesCentralDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  int checked = 0;
  for (int trial = 0; trial < 200 && checked < 20; ++trial) {
    // A perturbed copy of A and a random upright triangle through it.
    std::array<Vector3d, 6> p = {
        a0, a1, a2, Vector3d(0.3, 0.2, -0.4), Vector3d(0.5, 0.3, 0.5), Vector3d(0.1, 0.4, 0.4)};
    for (Vector3d& q : p) q += Vector3d(u(rng), u(rng), u(rng));
    Eigen::Matrix<double, 18, 1> g;
    const double length = crossingLength(p[0], p[1], p[2], p[3], p[4], p[5], &g);
    if (length < 0.05) continue;
    const double step = 1e-7;
    Eigen::Matrix<double, 18, 1> fd;
    for (int k = 0; k < 18; ++k) {
      auto plus = p, minus = p;
      plus[k / 3](k % 3) += step;
      minus[k / 3](k % 3) -= step;
      fd(k) = (crossingLength(plus[0], plus[1], plus[2], plus[3], plus[4], plus[5]) -
               crossingLength(minus[0], minus[1], minus[2], minus[3], minus[4], minus[5])) /
              (2 * step);
    }
    EXPECT_LT((g - fd).norm(), 1e-5 * fd.norm()) << "trial " << trial;
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

constexpr int kN = 9;          // vertices per side of each panel
constexpr double kSide = 0.2;  // metres
constexpr double kGap = 0.03;  // the upper panel hangs this far above the lower one

// Two square jersey panels (kN x kN vertices, kSide wide) in the plane z = 0, the second one offset by `offset`; no
// gravity.
model::ClothModel twoPanels(const Vector3d& offset) {
  model::ClothModel m;
  model::TriangleFabric jersey;
  jersey.stretchWarp = jersey.stretchWeft = 500.0;
  jersey.shear = 50.0;
  m.fabrics = {jersey};
  m.gravity.setZero();
  newton::appendGridPanel(m, kN, kN, kSide, kSide, Vector3d(0, 0, 0));
  newton::appendGridPanel(m, kN, kN, kSide, kSide, offset);
  return m;
}

// Two parallel square panels, the upper one's middle pushed 2 cm through the lower one (a drag that went too
// far), both held at their corners: released, the upper panel's own stretch pulls it back up.
model::ClothModel pushedThrough() {
  model::ClothModel m = twoPanels(Vector3d(0, 0, kGap));
  const int base = kN * kN;
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const double r = std::hypot(i - (kN - 1) / 2.0, j - (kN - 1) / 2.0) / ((kN - 1) / 2.0);
      m.positions(3 * (base + j * kN + i) + 2) -= std::max(0.0, 1.0 - r) * (kGap + 0.02);
    }
  for (int panel = 0; panel < 2; ++panel)
    for (int corner : {0, kN - 1, kN * (kN - 1), kN * kN - 1}) m.pinned.push_back(panel * base + corner);
  return m;
}

// Two free panels, each at its rest shape: A flat in z = 0, B upright in the plane x + y = 0.35, cutting off A's
// corner at (0.2, 0.2) along a 7 cm chord. Nothing but the contour pulls: it slides B off the corner.
model::ClothModel cornerCut() {
  model::ClothModel m = twoPanels(Vector3d::Zero());
  const Vector3d centre(0.175, 0.175, 0.0), along = Vector3d(1, -1, 0).normalized(), up(0, 0, 1);
  for (int v = kN * kN; v < m.numVertices(); ++v) {
    const Eigen::Vector2d r = m.restCoords.row(v).transpose();
    m.positions.segment<3>(3 * v) = centre + (r.x() - kSide / 2) * along + (r.y() - kSide / 2) * up;
  }
  return m;
}

Eigen::MatrixX3d rows(const Eigen::VectorXd& x) {
  Eigen::MatrixX3d out(x.size() / 3, 3);
  for (Eigen::Index v = 0; v < out.rows(); ++v) out.row(v) = x.segment<3>(3 * v).transpose();
  return out;
}

int crossings(const model::ClothModel& m, const Eigen::VectorXd& x) {
  return collision::countSelfIntersections(rows(x), m.triangles).count;
}

// Positions after 0.2 s with the drape's contact terms: self contact at 2 mm and 1000 N/m, and the contour pull held
// over each step unless withContour is false.
Eigen::VectorXd released(const model::ClothModel& m, bool withContour = true) {
  newton::ContactSetup setup;
  setup.selfCollision = true;
  setup.selfContact.thickness = 0.002;
  setup.selfContact.stiffness = 1000.0;
  setup.contourPull = newton::ContourPull::HeldOverTheStep;
  auto energies = newton::makeContactEnergies(setup, m.numVertices(), m.triangles, {});
  if (!withContour) {
    std::erase_if(energies, [](const auto& e) { return e->name() == "intersection_contour"; });
    EXPECT_EQ(energies.size(), 1u);
  }
  newton::NewtonSolver solver(m, newton::NewtonSettings{}, std::move(energies));
  while (solver.time() < 0.2) {
    const auto status = solver.step().status;
    EXPECT_NE(status, newton::NewtonStatus::Diverged) << "t = " << solver.time();
    if (status == newton::NewtonStatus::Diverged) break;
  }
  return solver.positions();
}

// The pull held over a step is the followed contour's gradient at the step's start, constant through the step, and
// its value changes linearly with it: against the followed term's own gradient at x_n and a move within the step.
TEST(IntersectionContour, TheHeldPullIsTheContoursGradientAtTheStepStart) {
  const model::ClothModel m = cornerCut();
  newton::ContactSetup setup;
  setup.selfCollision = true;
  setup.selfContact.thickness = 0.002;
  setup.selfContact.stiffness = 1000.0;
  auto followed = newton::makeContactEnergies(setup, m.numVertices(), m.triangles, {});
  setup.contourPull = newton::ContourPull::HeldOverTheStep;
  auto held = newton::makeContactEnergies(setup, m.numVertices(), m.triangles, {});
  const Eigen::VectorXd& x0 = m.positions;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(x0.size());
  newton::StepContext ctx;
  ctx.previousPositions = &x0;
  ctx.previousVelocities = &zero;
  ctx.h = 0.002;
  for (auto* energies : {&followed, &held})
    for (auto& e : *energies) e->beginStep(ctx);
  const auto contour = [](auto& energies) -> const newton::Energy& {
    for (auto& e : energies)
      if (e->name() == "intersection_contour") return *e;
    throw std::logic_error("no contour term");
  };
  Eigen::VectorXd expected = zero, at0 = zero, at1 = zero;
  contour(followed).addGradient(x0, expected);
  ASSERT_GT(expected.norm(), 0.0);  // the corner is cut: a pull
  // A move within the step: the panel B slid 5 mm along its chord, which changes the true contour.
  Eigen::VectorXd x1 = x0;
  for (int v = kN * kN; v < m.numVertices(); ++v) x1.segment<3>(3 * v) += 0.005 * Vector3d(1, -1, 0).normalized();
  contour(held).addGradient(x0, at0);
  contour(held).addGradient(x1, at1);
  EXPECT_LT((at0 - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LT((at1 - expected).norm(), 1e-12 * expected.norm());
  EXPECT_NEAR(contour(held).value(x1) - contour(held).value(x0), expected.dot(x1 - x0), 1e-12);
}

TEST(IntersectionContour, APanelPushedThroughAnotherComesBackOut) {
  const model::ClothModel m = pushedThrough();
  const int centre = (kN * kN) / 2;
  // How far the upper panel's centre lies above the lower panel's centre, metres.
  const auto above = [&](const Eigen::VectorXd& x) { return x(3 * (kN * kN + centre) + 2) - x(3 * centre + 2); };
  EXPECT_LT(above(m.positions), 0.0);  // placed through
  const Eigen::VectorXd x = released(m);
  const int before = crossings(m, m.positions), after = crossings(m, x);
  std::printf("panel pushed through: %d crossing pairs placed, %d after 0.2 s; its centre %.1f mm above the other's\n",
              before, after, 1e3 * above(x));
  EXPECT_GT(before, 10);
  EXPECT_EQ(after, 0);
  EXPECT_GT(above(x), 0.0);  // back on its own side
}

TEST(IntersectionContour, TheContourAloneSlidesACrossingPanelOff) {
  const model::ClothModel m = cornerCut();
  const int before = crossings(m, m.positions);
  const int withContour = crossings(m, released(m));
  const int penaltyOnly = crossings(m, released(m, false));
  std::printf("corner cut: %d crossing pairs placed; after 0.2 s %d with the contour, %d with the penalty alone\n",
              before, withContour, penaltyOnly);
  EXPECT_GT(before, 0);
  EXPECT_EQ(withContour, 0);
  EXPECT_GT(penaltyOnly, 0);  // the penalty, kept off the crossing triangles, does not pull them free
}

}  // namespace
}  // namespace drape
