// Point-to-surface distance against independent computations: a tilted plate meshed at two
// resolutions (distance 0) and shifted along its normal (the shift); icospheres at two resolutions, bounded by the
// sagitta of the coarse mesh's triangles; points beyond an edge and a corner of an open plate (hand-computed
// Euclidean distances); random points against a brute-force minimum over all triangles; bad surfaces.
#include "drape/collision/surface_distance.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "drape/collision/distance.h"
#include "drape/geometry/primitives.h"

namespace drape::collision {
namespace {

using Eigen::Vector3d;

// Flat parallelogram origin + s u + t v, s, t in [0, 1], split into nu x nv cells of two triangles each.
TriangleMesh makePlate(const Vector3d& origin, const Vector3d& u, const Vector3d& v, int nu, int nv) {
  TriangleMesh mesh;
  mesh.vertices.resize((nu + 1) * (nv + 1), 3);
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      const Vector3d p = origin + (double(i) / nu) * u + (double(j) / nv) * v;
      mesh.vertices.row(j * (nu + 1) + i) = p.transpose();
    }
  }
  mesh.triangles.resize(2 * nu * nv, 3);
  int f = 0;
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int a = j * (nu + 1) + i;
      const int b = a + 1;
      const int c = a + nu + 1;
      const int d = c + 1;
      mesh.triangles.row(f++) << a, b, d;
      mesh.triangles.row(f++) << a, d, c;
    }
  }
  return mesh;
}

// A plate tilted out of every coordinate plane, so that no test relies on axis-aligned boxes or zero coordinates.
struct TiltedFrame {
  Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  Vector3d origin = Vector3d(0.12, -0.31, 0.27);
  Vector3d u = rotation * Vector3d(0.8, 0.0, 0.0);  // metres
  Vector3d v = rotation * Vector3d(0.0, 0.6, 0.0);
  Vector3d normal = rotation * Vector3d::UnitZ();
};

// Largest sagitta R - sqrt(R^2 - rho^2) over the triangles of a mesh inscribed in a sphere of radius R, rho the
// triangle's circumradius: every point of the sphere lies within this distance of the inscribed mesh, and every
// point of the mesh lies within it of the sphere.
double maxSagitta(const TriangleMesh& mesh, double radius) {
  double worst = 0.0;
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    const Vector3d a = mesh.vertices.row(mesh.triangles(f, 0)).transpose();
    const Vector3d b = mesh.vertices.row(mesh.triangles(f, 1)).transpose();
    const Vector3d c = mesh.vertices.row(mesh.triangles(f, 2)).transpose();
    const double rho = (a - b).norm() * (b - c).norm() * (c - a).norm() / (2.0 * (b - a).cross(c - a).norm());
    worst = std::max(worst, radius - std::sqrt(radius * radius - rho * rho));
  }
  return worst;
}

TEST(SurfaceDistanceTest, SamePlateAtTwoResolutionsIsAtDistanceZero) {
  const TiltedFrame fr;
  const TriangleMesh coarse = makePlate(fr.origin, fr.u, fr.v, 10, 10);
  const TriangleMesh fine = makePlate(fr.origin, fr.u, fr.v, 37, 23);
  const Eigen::VectorXd fineToCoarse = distancesToSurface(fine.vertices, coarse);
  const Eigen::VectorXd coarseToFine = distancesToSurface(coarse.vertices, fine);
  ASSERT_EQ(fineToCoarse.size(), fine.vertexCount());
  ASSERT_EQ(coarseToFine.size(), coarse.vertexCount());
  EXPECT_LT(fineToCoarse.maxCoeff(), 1e-14);
  EXPECT_LT(coarseToFine.maxCoeff(), 1e-14);
}

TEST(SurfaceDistanceTest, PlateShiftedAlongItsNormalIsAtTheShift) {
  const TiltedFrame fr;
  const TriangleMesh coarse = makePlate(fr.origin, fr.u, fr.v, 10, 10);
  const SurfaceDistance query(coarse);
  for (const double shift : {0.003, -0.003, 0.25}) {
    const TriangleMesh fine = makePlate(fr.origin + shift * fr.normal, fr.u, fr.v, 37, 23);
    const Eigen::VectorXd d = query.distances(fine.vertices);
    ASSERT_EQ(d.size(), fine.vertexCount());
    for (int i = 0; i < fine.vertexCount(); ++i) {
      EXPECT_NEAR(d[i], std::abs(shift), 1e-12 * std::abs(shift)) << "shift " << shift << " vertex " << i;
    }
  }
}

TEST(SurfaceDistanceTest, IcospheresAtTwoResolutionsAreWithinTheSagitta) {
  const Vector3d center(0.2, -0.1, 0.4);
  const double radius = 1.0;
  const TriangleMesh coarse = makeIcosphere(center, radius, 2);
  // The fine sphere is rotated about its centre so that its vertices are not those of the coarse one.
  TriangleMesh fine = makeIcosphere(Vector3d::Zero(), radius, 4);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.4, Vector3d(-1.0, 0.5, 2.0).normalized()).toRotationMatrix();
  fine.vertices = (fine.vertices * rotation.transpose()).rowwise() + center.transpose();
  const double sagitta = maxSagitta(coarse, radius);
  ASSERT_GT(sagitta, 1e-3);  // the bound below is not trivially tight

  const SurfaceDistance query(coarse);
  const Eigen::VectorXd onSphere = query.distances(fine.vertices);
  ASSERT_EQ(onSphere.size(), fine.vertexCount());
  EXPECT_GE(onSphere.minCoeff(), 0.0);
  EXPECT_LE(onSphere.maxCoeff(), sagitta + 1e-12);
  // Points of the sphere over the middle of a coarse triangle really are that far: the bound is reached.
  EXPECT_GT(onSphere.maxCoeff(), 0.5 * sagitta);

  // Points at radius 1.5: the coarse mesh lies inside the unit sphere (distance >= 0.5), and the radial point of
  // the mesh is within the sagitta of the sphere (distance <= 0.5 + sagitta).
  Eigen::MatrixX3d outside = ((fine.vertices.rowwise() - center.transpose()) * 1.5).rowwise() + center.transpose();
  const Eigen::VectorXd off = query.distances(outside);
  for (int i = 0; i < fine.vertexCount(); ++i) {
    EXPECT_GE(off[i], 0.5 * radius - 1e-12) << "vertex " << i;
    EXPECT_LE(off[i], 0.5 * radius + sagitta + 1e-12) << "vertex " << i;
  }
  EXPECT_GT(off.maxCoeff(), 0.5 * radius + 0.5 * sagitta);
}

TEST(SurfaceDistanceTest, PointsBeyondAnEdgeOrACornerOfAnOpenPlate) {
  const TiltedFrame fr;
  const TriangleMesh plate = makePlate(fr.origin, fr.u, fr.v, 3, 2);
  const SurfaceDistance query(plate);
  const Vector3d uHat = fr.u.normalized();
  const Vector3d vHat = fr.v.normalized();
  const Vector3d& n = fr.normal;
  // Beyond the edge s = 1, 3 cm out in the plane and 4 cm off it: the nearest point is on the edge, 5 cm away.
  EXPECT_NEAR(query.distance(fr.origin + fr.u + 0.3 * fr.v + 0.03 * uHat + 0.04 * n), 0.05, 1e-12);
  // Beyond the edge t = 0, on the other side of the plane: sqrt(0.05^2 + 0.12^2) = 0.13.
  EXPECT_NEAR(query.distance(fr.origin + 0.55 * fr.u - 0.05 * vHat - 0.12 * n), 0.13, 1e-12);
  // Beyond the corner s = t = 1: sqrt(0.02^2 + 0.03^2 + 0.06^2) = 0.07.
  EXPECT_NEAR(query.distance(fr.origin + fr.u + fr.v + 0.02 * uHat + 0.03 * vHat + 0.06 * n), 0.07, 1e-12);
  // Beyond the corner s = t = 0, in the plane: sqrt(0.3^2 + 0.4^2) = 0.5.
  EXPECT_NEAR(query.distance(fr.origin - 0.3 * uHat - 0.4 * vHat), 0.5, 1e-12);
  // The batch call gives the same values as the single-point call.
  Eigen::MatrixX3d points(2, 3);
  points.row(0) = (fr.origin + fr.u + 0.3 * fr.v + 0.03 * uHat + 0.04 * n).transpose();
  points.row(1) = (fr.origin - 0.3 * uHat - 0.4 * vHat).transpose();
  const Eigen::VectorXd d = distancesToSurface(points, plate);
  ASSERT_EQ(d.size(), 2);
  EXPECT_NEAR(d[0], 0.05, 1e-12);
  EXPECT_NEAR(d[1], 0.5, 1e-12);
}

TEST(SurfaceDistanceTest, MatchesBruteForceOnACrumpledSurface) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 0.02);
  TriangleMesh surface = makeIcosphere(Vector3d(0.1, 0.2, 0.3), 0.4, 3);
  for (int i = 0; i < surface.vertexCount(); ++i)
    surface.vertices.row(i) += Eigen::RowVector3d(noise(rng), noise(rng), noise(rng));
  std::uniform_real_distribution<double> u(-0.6, 1.0);
  Eigen::MatrixX3d points(400, 3);
  for (int i = 0; i < points.rows(); ++i) points.row(i) << u(rng), u(rng), u(rng);
  const Eigen::VectorXd d = distancesToSurface(points, surface);
  ASSERT_EQ(d.size(), points.rows());
  for (int i = 0; i < points.rows(); ++i) {
    const Vector3d p = points.row(i).transpose();
    double best2 = std::numeric_limits<double>::infinity();
    for (int f = 0; f < surface.triangleCount(); ++f) {
      const auto corner = [&](int k) -> Vector3d { return surface.vertices.row(surface.triangles(f, k)).transpose(); };
      best2 = std::min(best2, closestPointTriangle(p, corner(0), corner(1), corner(2)).distanceSquared);
    }
    EXPECT_NEAR(d[i], std::sqrt(best2), 1e-12) << "point " << i;
  }
}

TEST(SurfaceDistanceTest, BadSurfacesThrowAndNoPointsGiveAnEmptyResult) {
  EXPECT_THROW(distancesToSurface(Eigen::MatrixX3d::Zero(3, 3), TriangleMesh{}), std::invalid_argument);
  TriangleMesh bad = makePlate(Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(), 1, 1);
  bad.triangles(1, 2) = 4;  // only 4 vertices
  EXPECT_THROW(SurfaceDistance{bad}, std::invalid_argument);
  bad.triangles(1, 2) = -1;
  EXPECT_THROW(SurfaceDistance{bad}, std::invalid_argument);
  const TriangleMesh plate = makePlate(Vector3d::Zero(), Vector3d::UnitX(), Vector3d::UnitY(), 1, 1);
  EXPECT_EQ(distancesToSurface(Eigen::MatrixX3d(0, 3), plate).size(), 0);
}

}  // namespace
}  // namespace drape::collision
