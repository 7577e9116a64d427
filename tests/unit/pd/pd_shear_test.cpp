// The preview's strain term (pd_system.h): stretch and shear as separate PD constraints, the shear one weighted
// with the fabric's shear stiffness. Energies are checked against the Newton drape's StVK membrane (an
// independent computation on Green strain), and a cloth loaded in shear against the shear-panel solution.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>

#include "drape/newton/stvk_membrane.h"
#include "drape/pd/grid_cloth.h"
#include "drape/pd/pd_system.h"
#include "drape/pd/preview_solver.h"

namespace drape::pd {
namespace {

using Mat32 = Eigen::Matrix<double, 3, 2>;

drape::model::TriangleFabric fabric(double warp, double weft, double shear) {
  drape::model::TriangleFabric f;
  f.stretchWarp = warp;
  f.stretchWeft = weft;
  f.shear = shear;
  return f;
}

// A 4 x 4 grid (both diagonal directions) of 0.3 x 0.2 m, placed by the affine map x = q a u (u: rest coords,
// a: 2 x 2 in-plane deformation, q: a 3D rotation onto a tilted plane).
drape::model::ClothModel deformedPatch(const drape::model::TriangleFabric& fab, const Eigen::Matrix2d& a) {
  GridClothOptions o;
  o.nx = 4;
  o.ny = 4;
  o.width = 0.3;
  o.height = 0.2;
  o.pinTopCorners = false;
  drape::model::ClothModel m = makeGridCloth(o);
  m.fabrics = {fab};
  const Eigen::Matrix3d q = Eigen::AngleAxisd(0.8, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  for (int v = 0; v < m.numVertices(); ++v) {
    const Eigen::Vector2d u = m.restCoords.row(v).transpose();
    m.positions.segment<3>(3 * v) = q.leftCols<2>() * (a * u) + Eigen::Vector3d(0.1, 0.2, -0.3);
  }
  return m;
}

// Preview settings with the fabric's shear stiffness in the strain term (the model these tests check).
PreviewSettings fabricShear() {
  PreviewSettings s;
  s.shearModel = ShearModelKind::Fabric;
  return s;
}

Eigen::MatrixX3d asRows(const Eigen::VectorXd& x) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(x.data(), x.size() / 3, 3);
}

// PD strain energy and StVK membrane energy of the patch under in-plane deformation a.
std::pair<double, double> energies(const drape::model::TriangleFabric& fab, const Eigen::Matrix2d& a,
                                   const PreviewSettings& s = fabricShear()) {
  const drape::model::ClothModel m = deformedPatch(fab, a);
  const PdSystem pd(m, s);
  const newton::StvkMembrane stvk(m);
  return {pd.strainEnergy(asRows(m.positions)), stvk.value(m.positions)};
}

TEST(PdShear, SmallPureShearEnergyMatchesStvkMembrane) {
  for (const double shear : {50.0, 250.0, 1000.0}) {
    const drape::model::TriangleFabric fab = fabric(5000.0, 3000.0, shear);
    // Symmetric pure shear (S = a, stretch part zero) and simple shear (a rotation on top).
    for (const Eigen::Matrix2d& a : {Eigen::Matrix2d((Eigen::Matrix2d() << 1.0, 0.005, 0.005, 1.0).finished()),
                                     Eigen::Matrix2d((Eigen::Matrix2d() << 1.0, 0.01, 0.0, 1.0).finished())}) {
      const auto [pd, stvk] = energies(fab, a);
      std::printf("[ PdShear ] shear %.0f N/m, a01 %.3f a10 %.3f: PD %.4e J, StVK %.4e J, ratio %.4f\n", shear,
                  a(0, 1), a(1, 0), pd, stvk, pd / stvk);
      ASSERT_GT(stvk, 0.0);
      EXPECT_NEAR(pd / stvk, 1.0, 0.03);
    }
  }
  // Rigid motion (the rotation q alone): no energy.
  const auto [pd, stvk] = energies(fabric(5000.0, 3000.0, 250.0), Eigen::Matrix2d::Identity());
  EXPECT_LT(pd, 1e-20);
  EXPECT_LT(stvk, 1e-20);
}

TEST(PdShear, SmallStretchEnergyMatchesStvkMembraneWithTightLimits) {
  const drape::model::TriangleFabric fab = fabric(5000.0, 3000.0, 250.0);
  PreviewSettings s = fabricShear();
  s.warpLimits = {1.0, 1.0};
  s.weftLimits = {1.0, 1.0};
  for (const Eigen::Vector2d& d : {Eigen::Vector2d(1.01, 1.0), Eigen::Vector2d(1.0, 0.99),
                                   Eigen::Vector2d(1.008, 0.995)}) {
    const auto [pd, stvk] = energies(fab, d.asDiagonal(), s);
    std::printf("[ PdShear ] stretch (%.3f, %.3f): PD %.4e J, StVK %.4e J, ratio %.4f\n", d.x(), d.y(), pd, stvk,
                pd / stvk);
    EXPECT_NEAR(pd / stvk, 1.0, 0.03);
  }
  // Within loose limits the stretch part is silent while the StVK membrane is not (strain limiting).
  s.warpLimits = {0.9, 1.1};
  EXPECT_LT(energies(fab, Eigen::Vector2d(1.05, 1.0).asDiagonal(), s).first, 1e-20);
  // The shear limit: no shear energy inside +-shearLimit, and only the excess beyond it outside.
  s.warpLimits = {1.0, 1.0};
  s.shearLimit = 0.01;
  const Eigen::Matrix2d sheared = (Eigen::Matrix2d() << 1.0, 0.005, 0.005, 1.0).finished();
  EXPECT_LT(energies(fab, sheared, s).first, 1e-20);
  const Eigen::Matrix2d beyond = (Eigen::Matrix2d() << 1.0, 0.03, 0.03, 1.0).finished();
  const Eigen::Matrix2d excess = (Eigen::Matrix2d() << 1.0, 0.02, 0.02, 1.0).finished();
  const double limited = energies(fab, beyond, s).first;
  s.shearLimit = 0.0;
  EXPECT_NEAR(limited, energies(fab, excess, s).first, 1e-12);
}

// ShearModelKind::Stretch is pd-dd's constraint (w_c / 2) |F_c - R clamp(S)_c|^2: a pure shear S01 = S10 = s
// costs A (kWarp + kWeft) / 2 s^2, the fabric's shear stiffness unused, and K has only the stretch weights.
TEST(PdShear, StretchHeldShearIsThePaperConstraint) {
  const drape::model::TriangleFabric fab = fabric(5000.0, 3000.0, 250.0);
  PreviewSettings s = fabricShear();
  s.shearModel = ShearModelKind::Stretch;
  const double shear = 0.005;
  const Eigen::Matrix2d a = (Eigen::Matrix2d() << 1.0, shear, shear, 1.0).finished();
  const double area = 0.3 * 0.2;
  EXPECT_NEAR(energies(fab, a, s).first, area * 4000.0 * shear * shear, 1e-9 * area * 4000.0 * shear * shear);
  const drape::model::ClothModel m = deformedPatch(fab, a);
  const PdSystem pd(m, s);
  EXPECT_TRUE(pd.stretchHoldsShear());
  for (const StrainConstraint& sc : pd.strains()) {
    EXPECT_EQ(sc.weightShear, 0.0);
    EXPECT_EQ(sc.columnWeight(0), sc.weightWarp);
  }
  // Its single projection is R clamp(S): rotation times identity for a pure shear within no limits.
  const Mat32 f = pd.deformationGradient(0, asRows(m.positions));
  const StrainProjection p = projectStrain(f, {}, {}, 0.0, true);
  EXPECT_NEAR((p.stretch.transpose() * p.stretch - Eigen::Matrix2d::Identity()).norm(), 0.0, 1e-12);
  EXPECT_LT((pd.project(0, asRows(m.positions)) - p.stretch).norm(), 1e-15);
}

TEST(PdShear, ProjectionsSplitStretchFromShear) {
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, 1.0, -0.3).normalized()).toRotationMatrix();
  // S = [[1.2, 0.1], [0.1, 0.9]] in the frame rot: F = R S with R = the first two columns of rot.
  const Eigen::Matrix2d s = (Eigen::Matrix2d() << 1.2, 0.1, 0.1, 0.9).finished();
  const Mat32 f = rot.leftCols<2>() * s;
  const StrainProjection p = projectStrain(f, {0.95, 1.05}, {0.95, 1.05}, 0.04);
  const Eigen::Matrix2d stretch = rot.leftCols<2>().transpose() * p.stretch;
  const Eigen::Matrix2d shear = rot.leftCols<2>().transpose() * p.shear;
  EXPECT_LT((rot.leftCols<2>() * stretch - p.stretch).norm(), 1e-12);  // stays in the triangle's plane
  EXPECT_LT((stretch - (Eigen::Matrix2d() << 1.05, 0.1, 0.1, 0.95).finished()).norm(), 1e-12);
  EXPECT_LT((shear - (Eigen::Matrix2d() << 1.2, 0.04, 0.04, 0.9).finished()).norm(), 1e-12);
  // Combined target: per column the weighted mean, weights w_c and w_shear.
  StrainConstraint sc;
  sc.weightWarp = 3.0;
  sc.weightWeft = 1.0;
  sc.weightShear = 1.0;
  const Mat32 t = combinedTarget(sc, p);
  EXPECT_LT((t.col(0) - (3.0 * p.stretch.col(0) + p.shear.col(0)) / 4.0).norm(), 1e-12);
  EXPECT_LT((t.col(1) - 0.5 * (p.stretch.col(1) + p.shear.col(1))).norm(), 1e-12);
  // A degenerate rest triangle (all weights 0) gets the stretch projection, finite.
  EXPECT_EQ(combinedTarget(StrainConstraint{}, p), p.stretch);
}

TEST(PdShear, SystemMatrixCarriesStretchPlusShearWeights) {
  const drape::model::TriangleFabric fab = fabric(5000.0, 3000.0, 250.0);
  const drape::model::ClothModel m = deformedPatch(fab, Eigen::Matrix2d::Identity());
  const PdSystem pd(m, fabricShear());
  const double area = 0.1 * (0.2 / 3.0) / 2.0;
  for (const StrainConstraint& sc : pd.strains()) {
    EXPECT_NEAR(sc.weightWarp, 5000.0 * area, 1e-9);
    EXPECT_NEAR(sc.weightShear, 250.0 * area, 1e-9);
    EXPECT_NEAR(sc.columnWeight(0), 5250.0 * area, 1e-9);
    EXPECT_NEAR(sc.columnWeight(1), 3250.0 * area, 1e-9);
  }
  // The strain stencil of a triangle: q = sum_c columnWeight(c) g_c g_c^T, so its 3 x 3 block reproduces the
  // combined-constraint energy sum_c w_c / 2 |F_c - P_c|^2 for a target P = 0: x^T q x / 2 per coordinate.
  const Eigen::MatrixX3d x = asRows(m.positions);
  const StrainConstraint& sc = pd.strains()[3];
  const Stencil& st = pd.stencils()[3];
  ASSERT_EQ(st.size, 3);
  Eigen::Matrix3d xs;
  for (int k = 0; k < 3; ++k) xs.row(k) = x.row(sc.vertices[k]);
  const Mat32 f = xs.transpose() * sc.g;
  const double quadratic = 0.5 * (xs.transpose() * st.q.topLeftCorner<3, 3>() * xs).trace();
  const double combined =
      0.5 * (sc.columnWeight(0) * f.col(0).squaredNorm() + sc.columnWeight(1) * f.col(1).squaredNorm());
  EXPECT_NEAR(quadratic, combined, 1e-12 * quadratic);
}

// A wide vertical wall of cloth (x right, y up) pinned along its bottom edge, loaded by a sideways body force
// (gravity along +x): simple shear, u_x(y) with G du/dy = rho g (H - y), G = kShear / 2 in the StVK convention
// (energy A kShear E01^2, E01 = gamma / 2), so the top moves rho g H^2 / kShear away from the side edges.
double shearedTopDisplacement(double shear, double* expected) {
  GridClothOptions o;
  o.nx = 37;
  o.ny = 7;
  o.width = 1.2;
  o.height = 0.2;
  o.pinTopCorners = false;
  drape::model::ClothModel m = makeGridCloth(o);
  m.fabrics = {fabric(5000.0, 5000.0, shear)};
  m.fabrics[0].bendWarp = m.fabrics[0].bendWeft = 0.0;  // in-plane problem
  const double g = 20.0;
  m.gravity = Eigen::Vector3d(g, 0.0, 0.0);
  for (int i = 0; i < o.nx; ++i) m.pinned.push_back(i);
  PreviewSettings s = fabricShear();
  s.timeStep = 0.05;  // quasi-static: the inertia term is small, the state settles within a few steps
  s.velocityDamping = 0.5;
  s.tolerance = 1e-9;
  // A soft shear mode under stiff stretch converges slowly in PD: about 1250 L-G iterations per step for
  // kShear / kStretch = 1/50 here (180 for 1/5). Capped at 400 the soft wall settles at twice the displacement.
  s.maxIterations = 3000;
  s.domains = 2;
  PreviewSolver solver(m, s);
  PreviewReport r;
  for (int k = 0; k < 8; ++k) {
    r = solver.step();
    EXPECT_NE(r.status, PreviewStatus::Diverged);
  }
  EXPECT_EQ(r.status, PreviewStatus::Converged);
  std::printf("[ PdShear ] shear %.0f N/m: %d L-G iterations in the last step\n", shear, r.iterations);
  const int top = (o.ny - 1) * o.nx + o.nx / 2;
  const Eigen::VectorXd& x = solver.positions();
  EXPECT_TRUE(x.allFinite());
  EXPECT_NEAR(x[3 * top + 2], 0.0, 1e-9);  // stays in its plane
  *expected = m.fabrics[0].density * g * o.height * o.height / shear;
  return x[3 * top] - m.positions[3 * top];
}

TEST(PdShear, LowShearFabricShearsMoreInProportion) {
  double expectedSoft = 0.0, expectedStiff = 0.0;
  const double soft = shearedTopDisplacement(100.0, &expectedSoft);
  const double stiff = shearedTopDisplacement(1000.0, &expectedStiff);
  std::printf("[ PdShear ] top displacement: shear 100 N/m %.4e m (shear panel %.4e), shear 1000 N/m %.4e m "
              "(shear panel %.4e), ratio %.2f (stiffness ratio 10)\n",
              soft, expectedSoft, stiff, expectedStiff, soft / stiff);
  EXPECT_GT(stiff, 0.0);
  EXPECT_GT(soft, stiff);
  EXPECT_GT(soft / stiff, 8.0);
  EXPECT_LT(soft / stiff, 12.0);
  // Against the shear-panel solution (linear elements give exact nodal values in 1D; the side edges and the
  // finite strain cost a little).
  EXPECT_NEAR(soft / expectedSoft, 1.0, 0.05);
  EXPECT_NEAR(stiff / expectedStiff, 1.0, 0.05);
}

}  // namespace
}  // namespace drape::pd
