// Icosphere and box: counts, closedness, outward orientation, volume against the exact value.
#include "drape/geometry/primitives.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace drape {
namespace {

TEST(PrimitivesTest, IcosphereCountsAndVerticesOnSphere) {
  const Eigen::Vector3d center(0.1, -0.2, 0.3);
  for (int s = 0; s <= 3; ++s) {
    const TriangleMesh sphere = makeIcosphere(center, 0.5, s);
    const int faces = 20 * (1 << (2 * s));
    EXPECT_EQ(sphere.triangleCount(), faces);
    EXPECT_EQ(sphere.vertexCount(), faces / 2 + 2);  // Euler: V - E + F = 2 with E = 3F/2
    for (int i = 0; i < sphere.vertexCount(); ++i) {
      EXPECT_NEAR((sphere.vertices.row(i).transpose() - center).norm(), 0.5, 1e-12);
    }
    EXPECT_TRUE(isClosedManifold(sphere)) << "subdivisions " << s;
  }
}

TEST(PrimitivesTest, IcosphereFacesPointOutward) {
  const Eigen::Vector3d center(1.0, 2.0, 3.0);
  const TriangleMesh sphere = makeIcosphere(center, 2.0, 2);
  for (int f = 0; f < sphere.triangleCount(); ++f) {
    const Eigen::Vector3d a = sphere.vertices.row(sphere.triangles(f, 0)).transpose();
    const Eigen::Vector3d b = sphere.vertices.row(sphere.triangles(f, 1)).transpose();
    const Eigen::Vector3d c = sphere.vertices.row(sphere.triangles(f, 2)).transpose();
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    EXPECT_GT(normal.dot((a + b + c) / 3.0 - center), 0.0) << "face " << f;
  }
}

TEST(PrimitivesTest, IcosphereVolumeConvergesToBallFromBelow) {
  const double r = 0.3;
  const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  double previousError = exact;
  for (int s = 0; s <= 5; ++s) {
    const double volume = signedVolume(makeIcosphere(Eigen::Vector3d(5.0, 0.0, -2.0), r, s));
    EXPECT_GT(volume, 0.0);
    EXPECT_LT(volume, exact);  // inscribed polyhedron
    const double error = exact - volume;
    EXPECT_LT(error, 0.5 * previousError) << "subdivisions " << s;  // error ~ h^2: quarters per level
    previousError = error;
  }
  EXPECT_LT(previousError / exact, 2e-3);
}

TEST(PrimitivesTest, BoxIsClosedOutwardWithExactVolume) {
  const Eigen::Vector3d lo(-1.0, 0.5, 2.0);
  const Eigen::Vector3d hi(0.5, 1.0, 4.0);
  const TriangleMesh box = makeBox(lo, hi);
  EXPECT_EQ(box.vertexCount(), 8);
  EXPECT_EQ(box.triangleCount(), 12);
  EXPECT_TRUE(isClosedManifold(box));
  EXPECT_NEAR(signedVolume(box), 1.5 * 0.5 * 2.0, 1e-12);
  const BoundingBox bounds = boundsOf(box.vertices);
  EXPECT_TRUE(bounds.min.isApprox(lo));
  EXPECT_TRUE(bounds.max.isApprox(hi));
  // Every face normal points away from the centre.
  const Eigen::Vector3d center = 0.5 * (lo + hi);
  for (int f = 0; f < 12; ++f) {
    const Eigen::Vector3d a = box.vertices.row(box.triangles(f, 0)).transpose();
    const Eigen::Vector3d b = box.vertices.row(box.triangles(f, 1)).transpose();
    const Eigen::Vector3d c = box.vertices.row(box.triangles(f, 2)).transpose();
    EXPECT_GT((b - a).cross(c - a).dot((a + b + c) / 3.0 - center), 0.0) << "face " << f;
  }
}

TEST(PrimitivesTest, FlippedMeshHasNegativeVolumeAndIsStillClosed) {
  TriangleMesh box = makeBox(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  box.triangles.col(1).swap(box.triangles.col(2));
  EXPECT_NEAR(signedVolume(box), -1.0, 1e-12);
  EXPECT_TRUE(isClosedManifold(box));
}

TEST(PrimitivesTest, ClosedManifoldRejectsOpenInconsistentAndBadMeshes) {
  const TriangleMesh box = makeBox(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());

  TriangleMesh open = box;  // one face removed: three edges used once
  open.triangles.conservativeResize(11, 3);
  EXPECT_FALSE(isClosedManifold(open));

  TriangleMesh inconsistent = box;  // one face flipped: its edges used twice in the same direction
  std::swap(inconsistent.triangles(0, 1), inconsistent.triangles(0, 2));
  EXPECT_FALSE(isClosedManifold(inconsistent));

  TriangleMesh doubled = box;  // a face repeated: its edges used three times
  doubled.triangles.conservativeResize(13, 3);
  doubled.triangles.row(12) = box.triangles.row(0);
  EXPECT_FALSE(isClosedManifold(doubled));

  TriangleMesh outOfRange = box;
  outOfRange.triangles(5, 1) = 8;
  EXPECT_FALSE(isClosedManifold(outOfRange));

  EXPECT_FALSE(isClosedManifold(TriangleMesh{}));
}

TEST(PrimitivesTest, InvalidArgumentsThrow) {
  EXPECT_THROW(makeIcosphere(Eigen::Vector3d::Zero(), 0.0, 1), std::invalid_argument);
  EXPECT_THROW(makeIcosphere(Eigen::Vector3d::Zero(), 1.0, -1), std::invalid_argument);
  EXPECT_THROW(makeBox(Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero()), std::invalid_argument);
}

}  // namespace
}  // namespace drape
