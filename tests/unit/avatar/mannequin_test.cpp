// The parametric mannequin: topology and fitted girths measured on the mesh, its arm pose, canonical order and levels.
// The fits of the shipped measurements and the distance to the real body GarmentCode's mean_all.yaml describes are
// slow tests (tests/slow/mannequin_fit_test.cpp).
#include "drape/avatar/mannequin.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "drape/avatar/avatar_loader.h"
#include "drape/avatar/body_measurements.h"
#include "drape/core/input_error.h"
#include "drape/io/mesh_export.h"
#include "mannequin_support.h"
#include "shared_data.h"

namespace drape {
namespace {

TEST(Mannequin, GarmentCodeMeanBodyIsClosedAndFitsItsMeasurements) {
  DRAPE_SHARED_FILE(file, "garmentcode/mean_all.yaml");
  expectValidMannequin(file);
}

TEST(Mannequin, ArmPoseAngleIsBelowTheHorizontal) {
  DRAPE_SHARED_FILE(file, "garmentcode/mean_all.yaml");
  BodyMeasurements m = loadBodyMeasurements(file);
  m.armPoseAngle = 0.0;  // T-pose: arms horizontal, fingertips far out at shoulder height
  MannequinOptions coarse;
  coarse.facetSize = 0.03;
  coarse.facetDistance = 0.005;
  const TriangleMesh tpose = makeMannequin(m, coarse);
  const BoundingBox box = boundsOf(tpose.vertices);
  const double reach = 0.5 * m.shoulderWidth + m.armLength;
  EXPECT_GT(box.max.x(), reach);
  EXPECT_LT(box.max.x(), reach + 0.25);
  // The extreme-x vertex sits at about shoulder-joint height.
  Eigen::Index tip = 0;
  tpose.vertices.col(0).maxCoeff(&tip);
  EXPECT_NEAR(tpose.vertices(tip, 1), mannequinLevels(m).neckBase - 0.09, 0.06);

  // mean_all's own arm: 45.5 degrees below the horizontal, so at wrist height the reach is ~cos(45.5) arm.
  const TriangleMesh& apose = mannequinFor(file);
  EXPECT_LT(boundsOf(apose.vertices).max.x(), 0.5 * m.shoulderWidth + std::cos(0.8) * m.armLength + 0.2);
}

// CGAL hands the surface's facets over in an order that follows memory addresses; the mannequin's own order is
// canonical, so that the same measurements give the same file in every run (CliMakeAvatar checks two processes).
TEST(Mannequin, MeshIsInCanonicalOrder) {
  const BodyMeasurements m = loadBodyMeasurements(test::assetsDir() / "avatars" / "female.yaml");
  MannequinOptions coarse;
  coarse.facetSize = 0.03;
  coarse.facetDistance = 0.005;
  const TriangleMesh a = makeMannequin(m, coarse);
  ASSERT_GT(a.vertices.rows(), 100);
  for (Eigen::Index i = 1; i < a.vertices.rows(); ++i) {
    const Eigen::RowVector3d p = a.vertices.row(i - 1), q = a.vertices.row(i);
    ASSERT_TRUE(std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3)) << "vertex " << i;
  }
  for (Eigen::Index f = 0; f < a.triangles.rows(); ++f) {
    ASSERT_LT(a.triangles(f, 0), a.triangles(f, 1)) << "triangle " << f;
    ASSERT_LT(a.triangles(f, 0), a.triangles(f, 2)) << "triangle " << f;
    if (f > 0) {
      const Eigen::RowVector3i s = a.triangles.row(f - 1), t = a.triangles.row(f);
      ASSERT_TRUE(std::lexicographical_compare(s.data(), s.data() + 3, t.data(), t.data() + 3)) << "triangle " << f;
    }
  }
}

TEST(Mannequin, InconsistentLandmarksAreInputErrors) {
  DRAPE_SHARED_FILE(file, "garmentcode/mean_all.yaml");
  BodyMeasurements m = loadBodyMeasurements(file);
  m.waistLine = 1.5;  // waist below the floor
  EXPECT_THROW(mannequinLevels(m), InputError);
}

// Without the optional landmark keys the levels are fixed fractions of the input's own height, and the girths
// still fit.
TEST(Mannequin, MissingLandmarksFollowTheHeight) {
  BodyMeasurements m = loadBodyMeasurements(test::assetsDir() / "avatars" / "male.yaml");
  m.headLength.reset();
  m.waistLine.reset();
  m.hipsLine.reset();
  m.crotchHipDiff.reset();
  m.vertBustLine.reset();
  m.height = 1.90;
  const MannequinLevels levels = mannequinLevels(m);
  EXPECT_NEAR(levels.top, 1.90, 1e-12);
  EXPECT_NEAR(levels.neckBase, 1.90 * (1 - 0.150), 1e-9);
  EXPECT_NEAR(levels.waist, 1.90 * (1 - 0.150 - 0.220), 1e-9);
  EXPECT_NEAR(levels.hips, 1.90 * (1 - 0.150 - 0.220 - 0.130), 1e-9);
  EXPECT_NEAR(levels.crotch, 1.90 * (1 - 0.150 - 0.220 - 0.130 - 0.050), 1e-9);
  EXPECT_NEAR(levels.bust, 1.90 * (1 - 0.150 - 0.125), 1e-9);
  EXPECT_NEAR(levels.underbust, levels.bust - 0.45 * (levels.bust - levels.waist), 1e-9);

  MannequinOptions coarse;
  coarse.facetSize = 0.015;
  const TriangleMesh mesh = makeMannequin(m, coarse);
  EXPECT_NEAR(boundsOf(mesh.vertices).max.y(), 1.90, 0.01);
  EXPECT_NEAR(torsoGirth(mesh, levels.bust), m.bust, 0.02);
  EXPECT_NEAR(torsoGirth(mesh, levels.waist), m.waist, 0.02);
  EXPECT_NEAR(torsoGirth(mesh, levels.hips), m.hips, 0.02);
  EXPECT_NEAR(thighGirth(mesh, levels.crotch), m.thigh, 0.02);
}

// The meshes shipped as the default mannequins are the smooth ones: no ledge at the hips, no rings on the arms.
TEST(Mannequin, ShippedMannequinsAreSmooth) {
  for (const char* name : {"female", "male"}) {
    SCOPED_TRACE(name);
    const auto dir = test::assetsDir() / "avatars";
    expectSmoothMannequin(loadAvatar(dir / (std::string(name) + ".obj")),
                          loadBodyMeasurements(dir / (std::string(name) + ".yaml")));
  }
}

// Writes assets/avatars/{female,male}.obj. Run with --gtest_also_run_disabled_tests.
TEST(Mannequin, DISABLED_WriteShippedAvatars) {
  for (const char* name : {"female", "male"}) {
    const auto dir = test::assetsDir() / "avatars";
    const auto yaml = dir / (std::string(name) + ".yaml");
    exportMesh(mannequinFor(yaml), dir / (std::string(name) + ".obj"));
  }
}

}  // namespace
}  // namespace drape
