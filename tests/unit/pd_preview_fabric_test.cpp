// The preview's softened fabric (solver.preview.courant_limit, preview_fabric.h): the Courant number against a
// hand computation and the cap. What it is for, the default t-shirt in cotton shirting, whose preview tears at the
// fabric's own stiffness and stays whole when softened, is a slow test (tests/slow/pd_preview_fabric_cotton_test.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "drape/pd/preview_fabric.h"

namespace drape::test {
namespace {

// A square of side `side` (metres) in two triangles, one fabric per triangle.
drape::model::ClothModel twoTriangleSquare(double side, const drape::model::TriangleFabric& a, const drape::model::TriangleFabric& b) {
  drape::model::ClothModel m;
  m.restCoords.resize(4, 2);
  m.restCoords << 0, 0, side, 0, side, side, 0, side;
  m.triangles.resize(2, 3);
  m.triangles << 0, 1, 2, 0, 2, 3;
  m.fabrics = {a, b};
  m.positions = Eigen::VectorXd::Zero(12);
  return m;
}

drape::model::TriangleFabric fabric(double warp, double weft, double shear, double density) {
  drape::model::TriangleFabric f;
  f.stretchWarp = warp;
  f.stretchWeft = weft;
  f.shear = shear;
  f.bendWarp = 3e-6;
  f.bendWeft = 2e-6;
  f.density = density;
  return f;
}

TEST(PreviewFabric, CourantNumberIsTheFastestWaveOverTheMeanEdge) {
  const double side = 0.02, h = 1.0 / 480.0;
  // Wave speeds sqrt(400 / 0.25) = 40 m/s and sqrt(100 / 0.5) = 14.1 m/s; edges: four sides and the diagonal twice.
  const drape::model::ClothModel m = twoTriangleSquare(side, fabric(400, 100, 10, 0.25), fabric(100, 50, 5, 0.5));
  const double meanEdge = side * (4.0 + 2.0 * std::sqrt(2.0)) / 6.0;
  EXPECT_NEAR(pd::courantNumber(m, h), 40.0 * h / meanEdge, 1e-12);
}

TEST(PreviewFabric, SoftensOnlyTheFabricsAboveTheLimitToTheLimit) {
  const double side = 0.02, h = 1.0 / 480.0;
  const drape::model::TriangleFabric stiff = fabric(6000, 4000, 60, 0.12), soft = fabric(300, 150, 20, 0.18);
  const drape::model::ClothModel m = twoTriangleSquare(side, stiff, soft);
  const double limit = 5.0;
  ASSERT_GT(pd::courantNumber(m, h), limit);
  const drape::model::ClothModel p = pd::previewFabricModel(m, h, limit);
  EXPECT_NEAR(pd::courantNumber(p, h), limit, 1e-9);
  // The stiff fabric: stretch and shear scaled by one factor (its anisotropy kept), the rest as it was.
  const double scale = p.fabrics[0].stretchWarp / stiff.stretchWarp;
  EXPECT_LT(scale, 1.0);
  EXPECT_NEAR(p.fabrics[0].stretchWeft, scale * stiff.stretchWeft, 1e-9);
  EXPECT_NEAR(p.fabrics[0].shear, scale * stiff.shear, 1e-12);
  EXPECT_EQ(p.fabrics[0].density, stiff.density);
  EXPECT_EQ(p.fabrics[0].bendWarp, stiff.bendWarp);
  EXPECT_EQ(p.fabrics[0].bendWeft, stiff.bendWeft);
  // The soft one (Courant number 40.8 h / mean edge, about 4.1) is below the limit: untouched.
  EXPECT_EQ(p.fabrics[1].stretchWarp, soft.stretchWarp);
  EXPECT_EQ(p.fabrics[1].shear, soft.shear);
  // No limit: the model as it is.
  EXPECT_EQ(pd::previewFabricModel(m, h, 0.0).fabrics[0].stretchWarp, stiff.stretchWarp);
}

}  // namespace
}  // namespace drape::test
