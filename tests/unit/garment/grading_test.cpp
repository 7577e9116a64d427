// A graded size (grading.scale, docs/FORMATS.md "Sizes") scales the whole pattern about its origin: the meshed panels'
// area by the square of the scale and their placed centroid by the scale; the size's body scales every length.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "drape/avatar/body_measurements.h"
#include "drape/scene/scene.h"
#include "drape/sim/scene_garment.h"
#include "shared_data.h"

namespace drape::test {
namespace {

struct Extent {
  double area = 0.0;          // m^2, of the rest (pattern) triangles
  Eigen::Vector3d centroid;  // area-weighted, of the placed triangles
};

Extent tshirtAt(const std::string& scale) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "tshirt.json";
  // No avatar, so that no fit moves the panels: the placement is the pattern's own.
  request.overrides = {{"mesh.target_edge_length", "0.03"}, {"avatar.file", ""}, {"grading.scale", scale}};
  const Garment g = buildSceneGarment(loadScene(request), nullptr);
  Extent e;
  e.centroid.setZero();
  double placedArea = 0.0;
  for (int t = 0; t < g.triangles.rows(); ++t) {
    const Eigen::Vector2d a = g.rest.row(g.triangles(t, 0)), b = g.rest.row(g.triangles(t, 1)),
                          c = g.rest.row(g.triangles(t, 2));
    e.area += 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    const Eigen::Vector3d p = g.positions.row(g.triangles(t, 0)), q = g.positions.row(g.triangles(t, 1)),
                          r = g.positions.row(g.triangles(t, 2));
    const double area = 0.5 * (q - p).cross(r - p).norm();
    e.centroid += area * (p + q + r) / 3.0;
    placedArea += area;
  }
  e.centroid /= placedArea;
  return e;
}

TEST(Grading, ScaledPatternHasTheAreaAndPlacementOfItsSize) {
  const Extent m = tshirtAt("1"), l = tshirtAt("1.1"), s = tshirtAt("0.9");
  EXPECT_NEAR(l.area / m.area, 1.1 * 1.1, 0.01 * 1.21);
  EXPECT_NEAR(s.area / m.area, 0.9 * 0.9, 0.01 * 0.81);
  // The panels are placed about the pattern's origin (the floor below the body's centre): their centroid moves with the
  // scale, to within the meshes' own difference (a few millimetres).
  EXPECT_LT((l.centroid - 1.1 * m.centroid).norm(), 0.005) << l.centroid.transpose() << " vs " << m.centroid.transpose();
  EXPECT_LT((s.centroid - 0.9 * m.centroid).norm(), 0.005) << s.centroid.transpose() << " vs " << m.centroid.transpose();
}

TEST(Grading, TheSizesBodyScalesEveryLengthAndKeepsTheArmPose) {
  const BodyMeasurements m = loadBodyMeasurements(assetsDir() / "avatars" / "female.yaml");
  const BodyMeasurements l = scaledBodyMeasurements(m, 1.05);
  EXPECT_DOUBLE_EQ(l.height, 1.05 * m.height);
  EXPECT_DOUBLE_EQ(l.bust, 1.05 * m.bust);
  EXPECT_DOUBLE_EQ(l.underbust, 1.05 * m.underbust);
  EXPECT_DOUBLE_EQ(l.waist, 1.05 * m.waist);
  EXPECT_DOUBLE_EQ(l.hips, 1.05 * m.hips);
  EXPECT_DOUBLE_EQ(l.shoulderWidth, 1.05 * m.shoulderWidth);
  EXPECT_DOUBLE_EQ(l.neckWidth, 1.05 * m.neckWidth);
  EXPECT_DOUBLE_EQ(l.armLength, 1.05 * m.armLength);
  EXPECT_DOUBLE_EQ(l.wrist, 1.05 * m.wrist);
  EXPECT_DOUBLE_EQ(l.thigh, 1.05 * m.thigh);
  ASSERT_TRUE(m.waistLine && m.hipsLine && m.headLength && m.crotchHipDiff && m.vertBustLine);
  EXPECT_DOUBLE_EQ(*l.waistLine, 1.05 * *m.waistLine);
  EXPECT_DOUBLE_EQ(*l.hipsLine, 1.05 * *m.hipsLine);
  EXPECT_DOUBLE_EQ(*l.headLength, 1.05 * *m.headLength);
  EXPECT_DOUBLE_EQ(*l.crotchHipDiff, 1.05 * *m.crotchHipDiff);
  EXPECT_DOUBLE_EQ(*l.vertBustLine, 1.05 * *m.vertBustLine);
  EXPECT_DOUBLE_EQ(l.armPoseAngle, m.armPoseAngle);
}

}  // namespace
}  // namespace drape::test
