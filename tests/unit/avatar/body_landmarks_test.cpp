// Body landmarks found on meshes made from known measurements: the library mannequins (and a T-pose variant), and
// GarmentCode's mean_all.obj against its own mean_all.yaml. The measurements are the independent expectation.
#include "drape/avatar/body_landmarks.h"

#include <gtest/gtest.h>

#include <cmath>

#include "drape/avatar/avatar_loader.h"
#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"
#include "drape/core/input_error.h"
#include "shared_data.h"

namespace drape {
namespace {

double degrees(double radians) {
  return radians * 180.0 / M_PI;
}

// Angle of an arm's direction below the horizontal, degrees.
double armDrop(const BodyAxis& arm) {
  return degrees(std::asin(-arm.direction.y()));
}

// Landmarks that the measurements fix whatever the mesh: height, shoulder width, arm angle, arms and legs on
// their sides and pointing the right way, the levels in order from the floor up.
void expectMatchesMeasurements(const BodyLandmarks& L, const BodyMeasurements& m) {
  EXPECT_NEAR(L.floor, 0.0, 0.01);
  EXPECT_NEAR(L.height, m.height, 0.01);
  // shoulder_w is taken between the acromions; the top outline turns down into the arm over the deltoid, a little
  // farther out (on the mannequin 2-3 cm on each side, docs/MANNEQUIN.md).
  EXPECT_NEAR(L.leftShoulder.x() - L.rightShoulder.x(), m.shoulderWidth, 0.06);
  EXPECT_NEAR(armDrop(L.leftArm), m.armPoseAngle, 5.0);
  EXPECT_NEAR(armDrop(L.rightArm), m.armPoseAngle, 5.0);
  EXPECT_GT(L.leftArm.direction.x(), 0.0);
  EXPECT_LT(L.rightArm.direction.x(), 0.0);
  EXPECT_LT(L.leftLeg.direction.y(), -0.95);
  EXPECT_LT(L.rightLeg.direction.y(), -0.95);
  EXPECT_GT(L.leftLeg.origin.x(), L.rightLeg.origin.x());
  EXPECT_LT(L.crotchHeight, L.hipHeight);
  EXPECT_LT(L.hipHeight, L.waistHeight);
  EXPECT_LT(L.waistHeight, L.bustHeight);
  EXPECT_LT(L.bustHeight, L.armpitHeight);
  EXPECT_LT(L.armpitHeight, L.leftShoulder.y());
  EXPECT_LT(L.leftShoulder.y(), L.neckHeight);
  EXPECT_LT(L.neckHeight, L.headTop.y());
  // The arm axes run through the arm: the shoulder point lies above the axis, within the arm's reach.
  for (const auto& [shoulder, arm] : {std::pair{L.leftShoulder, L.leftArm}, std::pair{L.rightShoulder, L.rightArm}}) {
    const Eigen::Vector3d q = shoulder - arm.origin;
    EXPECT_LT((q - arm.direction * q.dot(arm.direction)).norm(), 0.08);
  }
}

// Where the mannequin puts its levels (mannequinLevels, from the measurements' lengths).
void expectLevelsNear(const BodyLandmarks& L, const BodyMeasurements& m) {
  const MannequinLevels levels = mannequinLevels(m);
  EXPECT_NEAR(L.crotchHeight, levels.crotch, 0.03);
  EXPECT_NEAR(L.waistHeight, levels.waist, 0.05);
  EXPECT_NEAR(L.hipHeight, levels.hips, 0.09);
  EXPECT_NEAR(L.bustHeight, levels.bust, 0.06);
  EXPECT_NEAR(L.neckHeight, levels.neckBase, 0.05);
}

class MannequinLandmarks : public ::testing::TestWithParam<const char*> {};

TEST_P(MannequinLandmarks, MatchTheMeasurementsTheMannequinWasMadeFrom) {
  const BodyMeasurements m = loadBodyMeasurements(test::assetsDir() / "avatars" / (std::string(GetParam()) + ".yaml"));
  const BodyLandmarks L =
      findBodyLandmarks(loadAvatar(test::assetsDir() / "avatars" / (std::string(GetParam()) + ".obj")));
  expectMatchesMeasurements(L, m);
  expectLevelsNear(L, m);
}

INSTANTIATE_TEST_SUITE_P(Library, MannequinLandmarks, ::testing::Values("female", "male"));

TEST(BodyLandmarks, TPoseMannequinHasLevelArms) {
  BodyMeasurements m = loadBodyMeasurements(test::assetsDir() / "avatars" / "female.yaml");
  m.armPoseAngle = 0.0;
  MannequinOptions coarse;
  coarse.facetSize = 0.015;
  const BodyLandmarks L = findBodyLandmarks(makeMannequin(m, coarse));
  expectMatchesMeasurements(L, m);
}

TEST(BodyLandmarks, MeanAllMatchesItsMeasurementFile) {
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  DRAPE_SHARED_FILE(yaml, "garmentcode/mean_all.yaml");
  const BodyLandmarks L = findBodyLandmarks(loadAvatar(body));
  expectMatchesMeasurements(L, loadBodyMeasurements(yaml));
}

TEST(BodyLandmarks, SlicesOfABoxAreOneRectangle) {
  TriangleMesh box;
  box.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) box.vertices.row(i) << (i & 1 ? 2.0 : 0.0), (i & 2 ? 1.0 : 0.0), (i & 4 ? 3.0 : 0.0);
  box.triangles.resize(12, 3);
  box.triangles << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3,
      7, 5;
  const std::vector<SliceComponent> pieces = sliceMesh(box, 1, 0.4);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_NEAR(pieces[0].length, 2 * (2.0 + 3.0), 1e-12);
  EXPECT_NEAR(pieces[0].centroid.x(), 1.0, 1e-12);
  EXPECT_NEAR(pieces[0].centroid.y(), 0.4, 1e-12);
  EXPECT_NEAR(pieces[0].centroid.z(), 1.5, 1e-12);
  EXPECT_TRUE(sliceMesh(box, 1, 1.5).empty());
}

TEST(BodyLandmarks, ABoxIsNoBody) {
  TriangleMesh box;
  box.vertices.resize(4, 3);
  box.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  box.triangles.resize(4, 3);
  box.triangles << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  EXPECT_THROW(findBodyLandmarks(box), InputError);
}

}  // namespace
}  // namespace drape
