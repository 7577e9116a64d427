// Finite-difference checks of every Newton drape energy: gradients (relative error < 1e-5) and Hessians
// (< 1e-4 where exact) on randomly perturbed configurations; block-matrix product against Eigen's sparse one.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "drape/newton/body_forces.h"
#include "drape/newton/hinge_bending.h"
#include "drape/newton/springs.h"
#include "drape/newton/strain_rate_damping.h"
#include "drape/newton/stvk_membrane.h"
#include "energy_fd_check.h"
#include "newton_test_cloths.h"

using namespace drape::newton;

TEST(NewtonEnergy, MembraneGradientAndExactHessian) {
  for (unsigned seed : {1u, 2u, 3u}) {
    drape::model::ClothModel m = gridCloth(4, 0.05, 0.3, seed);
    StvkMembrane e(m);
    e.setExactHessian(true);
    checkEnergy(e, m.positions, true);
    e.setExactHessian(false);
    checkEnergy(e, m.positions, false);  // projected Hessian: SPD
  }
}

TEST(NewtonEnergy, MembraneStrainMatchesStretch) {
  // Uniform 10% warp stretch: E00 = (1.1^2 - 1) / 2, energy = area * 0.5 * kWarp * E00^2.
  drape::model::ClothModel m = gridCloth(3, 0.1, 0.3, 1);
  for (int v = 0; v < 9; ++v) m.positions.segment<3>(3 * v) << 1.1 * m.restCoords(v, 0), m.restCoords(v, 1), 0.0;
  StvkMembrane e(m);
  double e00 = 0.5 * (1.21 - 1.0);
  EXPECT_NEAR(e.value(m.positions), 0.04 * 0.5 * 5000.0 * e00 * e00, 1e-12);
}

TEST(NewtonEnergy, BendingGradientAndExactHessian) {
  for (unsigned seed : {4u, 5u, 6u}) {
    drape::model::ClothModel m = gridCloth(4, 0.05, 0.3, seed);
    HingeBending e(m);
    ASSERT_EQ(e.hinges().size(), 21u);  // 33 edges of a 4x4 grid minus 12 on the boundary
    e.setExactHessian(true);
    checkEnergy(e, m.positions, true);
    e.setExactHessian(false);
    checkEnergy(e, m.positions, false);  // Gauss-Newton: SPD
  }
}

// The assembly passes write each stencil's Hessian block by block: the membrane's from F's outer products with the
// stress clamped in closed form, the bending's Gauss-Newton outer product. They must equal the element Hessians
// formed whole and summed (elementHessian, clamped by Eigen's eigen solver; k_e grad(phi) grad(phi)^T), exact and
// projected, on a cloth compressed along the warp so that the clamp cuts.
TEST(NewtonEnergy, AssembledHessiansEqualTheElementHessiansSummed) {
  drape::model::ClothModel m = gridCloth(6, 0.05, 0.3, 11);
  for (int v = 0; v < m.numVertices(); ++v) m.positions(3 * v) *= 0.8;
  const Eigen::VectorXd& x = m.positions;
  const int n = static_cast<int>(x.size());
  auto scatter = [](Eigen::MatrixXd& dense, const auto& vertices, const auto& he) {
    const int k = static_cast<int>(vertices.size());
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k; ++b)
        dense.block<3, 3>(3 * vertices[a], 3 * vertices[b]) += he.template block<3, 3>(3 * a, 3 * b);
  };
  auto dense = [&](const Energy& e, const Eigen::VectorXd& at) {
    std::vector<std::pair<int, int>> pairs;
    e.addCouplings(pairs);
    BlockMatrix h;
    h.build(n / 3, pairs);
    e.addHessian(at, h);
    return Eigen::MatrixXd(h.toSparse());
  };
  StvkMembrane membrane(m);
  Eigen::MatrixXd byStencil[2];
  for (bool exact : {true, false}) {
    membrane.setExactHessian(exact);
    Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(n, n);
    for (const MembraneElement& e : membrane.elements()) scatter(expected, e.v, membrane.elementHessian(e, x));
    byStencil[exact] = dense(membrane, x);
    EXPECT_LT((byStencil[exact] - expected).norm(), 1e-12 * expected.norm()) << (exact ? "exact" : "projected");
  }
  EXPECT_GT((byStencil[1] - byStencil[0]).norm(), 1e-3 * byStencil[1].norm()) << "the clamp must cut somewhere";
  HingeBending bending(m);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(n, n);
  for (const Hinge& h : bending.hinges()) {
    double phi = 0.0;
    const Eigen::Matrix<double, 12, 1> grad = hingeBendGradient(h, x, true, phi);
    scatter(expected, h.v, Eigen::Matrix<double, 12, 12>(h.stiffness * grad * grad.transpose()));
  }
  ASSERT_GT(expected.norm(), 0.0);
  EXPECT_LT((dense(bending, x) - expected).norm(), 1e-12 * expected.norm());
}

TEST(NewtonEnergy, HingeAngleOfAKnownFold) {
  // Edge along x, wing 2 rotated by 90 degrees about it: |theta| = pi / 2; flat: 0.
  drape::model::ClothModel m = gridCloth(2, 1.0, 0.3, 1);
  HingeBending e(m);
  ASSERT_EQ(e.hinges().size(), 1u);
  Hinge h = e.hinges()[0];
  Eigen::VectorXd x = Eigen::VectorXd::Zero(12);
  x.segment<3>(3 * h.v[0]) << 0, 0, 0;
  x.segment<3>(3 * h.v[1]) << 1, 1, 0;
  x.segment<3>(3 * h.v[2]) << 1, 0, 0;
  x.segment<3>(3 * h.v[3]) << 0, 1, 0;
  EXPECT_NEAR(hingeAngle(h, x), 0.0, 1e-14);
  x.segment<3>(3 * h.v[3]) << 0.5, 0.5, std::sqrt(0.5);
  EXPECT_NEAR(std::abs(hingeAngle(h, x)), M_PI / 2, 1e-12);
}

TEST(NewtonEnergy, SpringsGravityDrag) {
  drape::model::ClothModel m = gridCloth(3, 0.1, 0.3, 7);
  StitchSprings stitches({{0, 8}, {2, 6}}, 1e3);
  checkEnergy(stitches, m.positions, true);
  PinSprings pins({1, 4}, {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3)}, 1e3);
  checkEnergy(pins, m.positions, true);
  Eigen::VectorXd mass = lumpedVertexMasses(m);
  EXPECT_NEAR(mass.sum(), 0.12 * 0.04, 1e-15);
  Gravity gravity(mass, Eigen::Vector3d(0, -9.81, 0));
  Eigen::VectorXd g = gradientOf(gravity, m.positions);
  EXPECT_NEAR(g.sum(), 9.81 * mass.sum(), 1e-12);
  Eigen::VectorXd previous = m.positions * 0.9, vel = Eigen::VectorXd::Zero(m.positions.size());
  AirDrag drag(mass, 5.0);
  drag.beginStep({&previous, &vel, 1e-3, 0.0, 1.0, {}});
  checkEnergy(drag, m.positions, true);
  // Force = -alpha m v with v = (x - x_n) / h.
  Eigen::VectorXd gd = gradientOf(drag, m.positions);
  EXPECT_NEAR(gd(3), 5.0 * mass(1) * (m.positions(3) - previous(3)) / 1e-3, 1e-12);
}

TEST(NewtonEnergy, DissipationPotentials) {
  drape::model::ClothModel m = gridCloth(4, 0.05, 0.3, 8);
  Eigen::VectorXd previous = gridCloth(4, 0.05, 0.3, 9).positions, vel = Eigen::VectorXd::Zero(previous.size());
  StepContext ctx{&previous, &vel, 1e-3, 0.0, 1.0, {}};
  StvkMembrane membrane(m);
  MembraneDissipation stretch(membrane.elements(), 1e-2);
  stretch.beginStep(ctx);
  checkEnergy(stretch, m.positions, true);
  HingeBending bending(m);
  BendingDissipation bend(bending.hinges(), 1e-1);
  bend.beginStep(ctx);
  checkEnergy(bend, m.positions, true);
  // Rigid translation has zero strain rate: no dissipation.
  Eigen::VectorXd moved = previous;
  for (int v = 0; v < 16; ++v) moved.segment<3>(3 * v) += Eigen::Vector3d(1e-3, -2e-3, 5e-4);
  EXPECT_NEAR(stretch.value(moved), 0.0, 1e-15);
  EXPECT_NEAR(bend.value(moved), 0.0, 1e-15);
}

TEST(NewtonBlockMatrix, MultiplyMatchesSparseWithDynamicBlocks) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n01;
  BlockMatrix a(5, {{0, 1}, {1, 2}, {3, 4}, {2, 0}});
  for (auto [i, j] : std::vector<std::pair<int, int>>{{0, 0}, {0, 1}, {2, 1}, {3, 4}, {1, 4}, {4, 4}, {2, 0}}) {
    Eigen::Matrix3d b = Eigen::Matrix3d::NullaryExpr([&] { return n01(rng); });
    if (i == j) b = (b + b.transpose()).eval();  // diagonal blocks of a symmetric matrix are symmetric
    a.addBlock(i, j, b);
  }
  EXPECT_EQ(a.dynamicBlockCount(), 1);  // (1, 4) is outside the static pattern
  Eigen::VectorXd x = Eigen::VectorXd::NullaryExpr(15, [&] { return n01(rng); });
  Eigen::SparseMatrix<double> s = a.toSparse();
  EXPECT_LT((a * x - s * x).norm(), 1e-12);
  EXPECT_LT((Eigen::MatrixXd(s) - Eigen::MatrixXd(s).transpose()).norm(), 1e-14);
  a.setZero();
  EXPECT_EQ(a.dynamicBlockCount(), 0);
  EXPECT_EQ((a * x).norm(), 0.0);
}
