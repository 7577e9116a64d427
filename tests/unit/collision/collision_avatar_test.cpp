// Avatar collider: signed distance to an icosphere and to a box against the analytic shapes, inside and outside,
// and the closest point against an all-triangles search; a hinted query answers as the unhinted one, also where it
// searches only the hint's neighbourhood, and a moving point's list of nearby triangles answers as a full query.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "drape/collision/avatar_collider.h"
#include "drape/geometry/primitives.h"

namespace drape::collision {
namespace {

using Eigen::Vector3d;

// A random direction: a point of the cube [-1, 1]^3 drawn with u, normalised.
Vector3d randomDirection(std::mt19937& rng, std::uniform_real_distribution<double>& u) {
  Vector3d dir(u(rng), u(rng), u(rng));
  dir.normalize();
  return dir;
}

// Squared distance from p to triangle f of mesh.
double triangleDistanceSquared(const TriangleMesh& mesh, int f, const Vector3d& p) {
  return closestPointTriangle(p, mesh.vertices.row(mesh.triangles(f, 0)), mesh.vertices.row(mesh.triangles(f, 1)),
                              mesh.vertices.row(mesh.triangles(f, 2)))
      .distanceSquared;
}

// The exhaustive minimum over all triangles: the reference for the collider's tree and neighbourhood searches.
double closestDistance(const TriangleMesh& mesh, const Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (int f = 0; f < mesh.triangleCount(); ++f) best = std::min(best, triangleDistanceSquared(mesh, f, p));
  return std::sqrt(best);
}

// A sphere of radius 0.2 with bumps, so that neighbouring triangles compete and differ in size.
TriangleMesh lumpySphere() {
  TriangleMesh mesh = makeIcosphere(Vector3d::Zero(), 0.2, 4);
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const Vector3d p = mesh.vertices.row(v);
    mesh.vertices.row(v) *= 1.0 + 0.08 * std::sin(23.0 * p.x()) * std::cos(17.0 * p.y() + 11.0 * p.z());
  }
  return mesh;
}

TEST(CollisionAvatarTest, IcosphereSignedDistanceMatchesSphere) {
  const Vector3d centre(0.1, 1.2, -0.3);
  const double radius = 0.3;
  const TriangleMesh mesh = makeIcosphere(centre, radius, 4);
  const AvatarCollider collider(mesh);
  // The polyhedron lies between its inradius and the sphere: for a point at distance r from the centre the mesh
  // distance differs from |r - radius| by at most the sagitta (radius - inradius).
  const double sagitta = 1.5e-3;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int inside = 0;
  for (int k = 0; k < 500; ++k) {
    const Vector3d dir = randomDirection(rng, u);
    const double r = radius * (0.2 + 1.6 * (k % 100) / 100.0);
    const Vector3d p = centre + r * dir;
    const double analytic = r - radius;
    SurfacePoint s;
    ASSERT_TRUE(collider.closest(p, s));
    EXPECT_NEAR(s.signedDistance, analytic, sagitta) << "r = " << r;
    if (std::abs(analytic) > sagitta) {
      EXPECT_EQ(s.signedDistance < 0, analytic < 0) << "r = " << r;
    }
    EXPECT_NEAR(s.normal.norm(), 1.0, 1e-12);
    EXPECT_GT(s.normal.dot(dir), 0.95);  // outward gradient, inside and outside
    EXPECT_NEAR(collider.signedDistance(p), s.signedDistance, 0.0);
    if (analytic < 0) ++inside;
    // Unsigned distance equals the exhaustive minimum over all triangles.
    EXPECT_NEAR(std::abs(s.signedDistance), closestDistance(mesh, p), 1e-13);
  }
  EXPECT_GT(inside, 100);
}

// Exact signed distance of an axis-aligned box.
double boxDistance(const Vector3d& p, const Vector3d& lo, const Vector3d& hi) {
  const Vector3d c = 0.5 * (lo + hi);
  const Vector3d h = 0.5 * (hi - lo);
  const Vector3d q = (p - c).cwiseAbs() - h;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

TEST(CollisionAvatarTest, BoxSignIsRightNearEdgesAndCorners) {
  const Vector3d lo(-0.2, 0.0, -0.1), hi(0.3, 0.4, 0.2);
  const AvatarCollider collider(makeBox(lo, hi));
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-0.5, 0.6);
  for (int k = 0; k < 2000; ++k) {
    const Vector3d p(u(rng), u(rng), u(rng));
    EXPECT_NEAR(collider.signedDistance(p), boxDistance(p, lo, hi), 1e-12) << p.transpose();
  }
  // Points just outside a corner and an edge, where only the vertex / edge pseudo-normal gives the sign.
  EXPECT_NEAR(collider.signedDistance(hi + Vector3d(1e-4, 2e-4, 1e-4)), std::sqrt(6e-8), 1e-12);
  EXPECT_NEAR(collider.signedDistance(Vector3d(0.0, 0.4 + 1e-5, 0.2 + 1e-5)), std::sqrt(2e-10), 1e-12);
  EXPECT_NEAR(collider.signedDistance(hi - Vector3d(1e-3, 2e-3, 3e-3)), -1e-3, 1e-12);
}

TEST(CollisionAvatarTest, BoundedQueryReportsNothingBeyondTheBound) {
  const AvatarCollider collider(makeIcosphere(Vector3d::Zero(), 1.0, 2));
  SurfacePoint s;
  EXPECT_FALSE(collider.closest(Vector3d(3, 0, 0), s, 1.5));
  EXPECT_TRUE(collider.closest(Vector3d(3, 0, 0), s, 2.5));
  EXPECT_NEAR(s.signedDistance, 2.0, 0.05);
}

// The hint only seeds the search bound: good, poor, out-of-range and beyond-the-bound hints all give the
// unhinted answer (same point and distance; the triangle may differ only where two share the closest point).
TEST(CollisionAvatarTest, HintedQueryAnswersAsTheUnhintedOne) {
  const AvatarCollider collider(makeIcosphere(Vector3d::Zero(), 0.2, 3));
  const int faces = collider.mesh().triangleCount();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.35, 0.35);
  std::uniform_int_distribution<int> face(0, faces - 1);
  int found = 0, missed = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vector3d p(u(rng), u(rng), u(rng));
    const double bound = k % 2 ? 0.05 : std::numeric_limits<double>::infinity();
    SurfacePoint plain;
    const bool hit = collider.closest(p, plain, bound);
    (hit ? found : missed) += 1;
    SurfacePoint near;  // the nearest triangle of a nearby point: the hint a moving vertex gets
    collider.closest(p + Vector3d(0.003, -0.002, 0.001), near);
    for (const int hint : {near.triangle, face(rng), -1, faces + 7}) {
      SurfacePoint hinted;
      ASSERT_EQ(collider.closest(p, hinted, bound, hint), hit) << p.transpose() << " hint " << hint;
      if (!hit) continue;
      EXPECT_NEAR(hinted.signedDistance, plain.signedDistance, 1e-12);
      EXPECT_LT((hinted.closest - plain.closest).norm(), 1e-12);
      EXPECT_LT((hinted.normal - plain.normal).norm(), 1e-9);
    }
  }
  EXPECT_GT(found, 500);  // both outcomes of the bounded query are exercised
  EXPECT_GT(missed, 500);
}

// Near the surface with a nearby hint, the query searches only the hint's neighbourhood (hintRadius()); its answer
// is still the closest point over all triangles, on a lumpy mesh whose triangles differ in size.
TEST(CollisionAvatarTest, HintedQueryNearTheSurfaceFindsTheClosestOfAllTriangles) {
  const TriangleMesh mesh = lumpySphere();
  const AvatarCollider collider(mesh);
  const double radius = collider.hintRadius();
  ASSERT_GT(radius, 0.0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int local = 0;
  for (int k = 0; k < 4000; ++k) {
    SurfacePoint onSurface;
    ASSERT_TRUE(collider.closest(0.2 * randomDirection(rng, u), onSurface));
    // A point up to radius / 3 off the surface, hinted with the triangle of a point up to radius / 6 away.
    const Vector3d p = onSurface.closest + (radius / 3.0) * u(rng) * onSurface.normal;
    SurfacePoint previous;
    ASSERT_TRUE(collider.closest(p + (radius / 6.0) * Vector3d(u(rng), u(rng), u(rng)).normalized(), previous));
    const double bound = k % 2 ? 0.4 * radius : std::numeric_limits<double>::infinity();
    const double best = closestDistance(mesh, p);
    const double hintDistance = std::sqrt(triangleDistanceSquared(mesh, previous.triangle, p));
    local += hintDistance + std::min(hintDistance, bound) <= radius;
    SurfacePoint hinted;
    const bool hit = collider.closest(p, hinted, bound, previous.triangle);
    ASSERT_EQ(hit, best < bound) << p.transpose();
    if (!hit) continue;
    EXPECT_NEAR(std::abs(hinted.signedDistance), best, 1e-13) << p.transpose();
    SurfacePoint plain;
    ASSERT_TRUE(collider.closest(p, plain, bound));
    EXPECT_NEAR(hinted.signedDistance, plain.signedDistance, 1e-13);
    EXPECT_LT((hinted.closest - plain.closest).norm(), 1e-12);
  }
  EXPECT_GT(local, 3000);  // most queries took the neighbourhood search
}

// Points wandering near a lumpy surface keep their NearbyTriangles from query to query. Every answer, bounded or
// not, must be the closest point over all triangles (and that of the plain query), whether the list settled it or
// a full query did; most small moves must be settled by the list (its centre stays where it was built).
TEST(CollisionAvatarTest, NearbyTrianglesAnswerAsTheFullQueryAlongAPath) {
  const TriangleMesh mesh = lumpySphere();
  const AvatarCollider collider(mesh);
  const double r = collider.reuseRadius();
  ASSERT_GT(r, 0.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int queries = 0, settled = 0, hits = 0, misses = 0;
  for (int walker = 0; walker < 60; ++walker) {
    SurfacePoint start;
    ASSERT_TRUE(collider.closest(0.2 * randomDirection(rng, u), start));
    Vector3d p = start.closest + 2.0 * r * u(rng) * start.normal;  // up to 2 r inside or outside
    NearbyTriangles nearby;
    for (int k = 0; k < 80; ++k) {
      // Small moves and jumps of a few reuse radii; the point stays within 5 r of the surface.
      const double lengths[] = {0.1, 0.3, 0.2, 1.5, 0.1, 0.2, 3.0};
      const double length = lengths[k % 7] * r;
      p += length * Vector3d(u(rng), u(rng), u(rng)).normalized();
      SurfacePoint onSurface;
      ASSERT_TRUE(collider.closest(p, onSurface));
      if (std::abs(onSurface.signedDistance) > 5.0 * r) p = onSurface.closest + 4.0 * r * u(rng) * onSurface.normal;
      const double bound = k % 3 == 0 ? std::numeric_limits<double>::infinity() : (k % 3 == 1 ? 2.0 * r : 0.5 * r);
      const Vector3d centre = nearby.center;
      const bool listed = nearby.complete > 0.0;
      SurfacePoint answer;
      const bool hit = collider.closest(p, answer, bound, nearby);
      ++queries;
      settled += listed && nearby.center == centre;
      const double best = closestDistance(mesh, p);
      ASSERT_EQ(hit, best < bound) << p.transpose() << " bound " << bound;
      (hit ? hits : misses) += 1;
      if (!hit) continue;
      EXPECT_NEAR(std::abs(answer.signedDistance), best, 1e-13) << p.transpose();
      SurfacePoint plain;
      ASSERT_TRUE(collider.closest(p, plain, bound));
      EXPECT_NEAR(answer.signedDistance, plain.signedDistance, 1e-13);
      EXPECT_LT((answer.closest - plain.closest).norm(), 1e-12);
      EXPECT_LT((answer.normal - plain.normal).norm(), 1e-9);
    }
  }
  std::printf("%d queries: %d settled by the list, %d hits, %d misses\n", queries, settled, hits, misses);
  EXPECT_GT(settled, queries / 2);  // the list settled most queries
  EXPECT_GT(hits, queries / 4);     // both outcomes of the bounded queries are exercised
  EXPECT_GT(misses, queries / 20);
}

}  // namespace
}  // namespace drape::collision
