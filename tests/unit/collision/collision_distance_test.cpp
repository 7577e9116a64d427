// Point-triangle and edge-edge closest points against hand-computed answers in every Voronoi region and against
// dense sampling on random inputs; AABB helpers against direct computation.
#include <gtest/gtest.h>

#include <random>

#include "drape/collision/aabb.h"
#include "drape/collision/distance.h"

namespace drape::collision {
namespace {

using Eigen::Vector3d;

TEST(CollisionDistanceTest, PointTriangleEveryRegion) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  struct Case {
    Vector3d p;
    Vector3d closest;
    TriangleRegion region;
  };
  const Case cases[] = {
      {{0.2, 0.3, 0.5}, {0.2, 0.3, 0}, TriangleRegion::Face},
      {{0.2, 0.3, -0.5}, {0.2, 0.3, 0}, TriangleRegion::Face},
      {{-1, -1, 0.3}, {0, 0, 0}, TriangleRegion::VertexA},
      {{2, -0.5, 0.1}, {1, 0, 0}, TriangleRegion::VertexB},
      {{-0.5, 3, 0}, {0, 1, 0}, TriangleRegion::VertexC},
      {{0.5, -1, 0.2}, {0.5, 0, 0}, TriangleRegion::EdgeAB},
      {{1, 1, 0.4}, {0.5, 0.5, 0}, TriangleRegion::EdgeBC},
      {{-2, 0.25, -0.1}, {0, 0.25, 0}, TriangleRegion::EdgeCA},
  };
  for (const Case& k : cases) {
    const PointTriangleResult r = closestPointTriangle(k.p, a, b, c);
    EXPECT_EQ(r.region, k.region) << k.p.transpose();
    EXPECT_NEAR((r.closest - k.closest).norm(), 0.0, 1e-14) << k.p.transpose();
    EXPECT_NEAR(r.distanceSquared, (k.p - k.closest).squaredNorm(), 1e-14);
    EXPECT_NEAR((r.barycentric[0] * a + r.barycentric[1] * b + r.barycentric[2] * c - r.closest).norm(), 0.0, 1e-14);
  }
}

TEST(CollisionDistanceTest, PointTriangleMatchesDenseSampling) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 300;
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Vector3d p = 2.0 * Vector3d(u(rng), u(rng), u(rng));
    const PointTriangleResult r = closestPointTriangle(p, a, b, c);
    ASSERT_GE(r.barycentric.minCoeff(), -1e-12);
    ASSERT_NEAR(r.barycentric.sum(), 1.0, 1e-12);
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const Vector3d q = a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n);
        best = std::min(best, (p - q).norm());
      }
    }
    const double d = std::sqrt(r.distanceSquared);
    const double spacing = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()}) / n;
    EXPECT_LE(d, best + 1e-12);        // nothing sampled is closer
    EXPECT_GE(d, best - 2 * spacing);  // and the sampling gets as close as its spacing
  }
}

TEST(CollisionDistanceTest, DegenerateTriangleUsesEdges) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(2, 0, 0);  // collinear
  const PointTriangleResult r = closestPointTriangle(Vector3d(1.5, 1, 0), a, b, c);
  EXPECT_NEAR(r.distanceSquared, 1.0, 1e-14);
  EXPECT_NEAR((r.closest - Vector3d(1.5, 0, 0)).norm(), 0.0, 1e-14);
}

TEST(CollisionDistanceTest, EdgeEdgeHandMadeCases) {
  // Crossing skew edges: closest points at the interior crossing.
  EdgeEdgeResult r = closestPointsEdgeEdge({-1, 0, 0}, {1, 0, 0}, {0, -1, 1}, {0, 1, 1});
  EXPECT_NEAR(r.s, 0.5, 1e-14);
  EXPECT_NEAR(r.t, 0.5, 1e-14);
  EXPECT_NEAR(r.distanceSquared, 1.0, 1e-14);
  EXPECT_FALSE(r.parallel);
  // Endpoint to interior.
  r = closestPointsEdgeEdge({0, 0, 0}, {1, 0, 0}, {2, -1, 0.5}, {2, 1, 0.5});
  EXPECT_NEAR(r.s, 1.0, 1e-14);
  EXPECT_NEAR(r.t, 0.5, 1e-14);
  EXPECT_NEAR(r.distanceSquared, 1.25, 1e-14);
  // Parallel, overlapping: distance is the gap.
  r = closestPointsEdgeEdge({0, 0, 0}, {2, 0, 0}, {1, 0.3, 0}, {3, 0.3, 0});
  EXPECT_TRUE(r.parallel);
  EXPECT_NEAR(r.distanceSquared, 0.09, 1e-14);
  // Parallel, disjoint along the line: endpoint to endpoint.
  r = closestPointsEdgeEdge({0, 0, 0}, {1, 0, 0}, {3, 0.4, 0}, {2, 0.4, 0});
  EXPECT_NEAR(r.distanceSquared, 1.0 + 0.16, 1e-14);
  EXPECT_NEAR(r.s, 1.0, 1e-14);
  EXPECT_NEAR(r.t, 1.0, 1e-14);
  // Degenerate (point) edge.
  r = closestPointsEdgeEdge({0.5, 1, 0}, {0.5, 1, 0}, {0, 0, 0}, {1, 0, 0});
  EXPECT_NEAR(r.distanceSquared, 1.0, 1e-14);
  EXPECT_NEAR(r.t, 0.5, 1e-14);
}

TEST(CollisionDistanceTest, EdgeEdgeMatchesDenseSampling) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 400;
  for (int trial = 0; trial < 200; ++trial) {
    const Vector3d p0(u(rng), u(rng), u(rng)), p1(u(rng), u(rng), u(rng));
    Vector3d q0(u(rng), u(rng), u(rng)), q1(u(rng), u(rng), u(rng));
    if (trial % 4 == 0) q1 = q0 + 0.7 * (p1 - p0);  // exactly parallel
    const EdgeEdgeResult r = closestPointsEdgeEdge(p0, p1, q0, q1);
    ASSERT_GE(r.s, 0.0);
    ASSERT_LE(r.s, 1.0);
    ASSERT_GE(r.t, 0.0);
    ASSERT_LE(r.t, 1.0);
    const double d = std::sqrt(r.distanceSquared);
    EXPECT_NEAR(d, ((p0 + r.s * (p1 - p0)) - (q0 + r.t * (q1 - q0))).norm(), 1e-12);
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i) {
      const Vector3d a = p0 + (p1 - p0) * (double(i) / n);
      // For a fixed point the closest point on the other segment is exact.
      const PointSegmentResult s = closestPointSegment(a, q0, q1);
      best = std::min(best, std::sqrt(s.distanceSquared));
    }
    EXPECT_LE(d, best + 1e-12);
    EXPECT_GE(d, best - (p1 - p0).norm() / n);
  }
}

TEST(CollisionDistanceTest, BoxHelpers) {
  BoundingBox a;
  a.min = Vector3d(0, 0, 0);
  a.max = Vector3d(1, 1, 1);
  BoundingBox b;
  b.min = Vector3d(1, 0.5, 0.5);
  b.max = Vector3d(2, 2, 2);
  EXPECT_TRUE(overlaps(a, b));  // touching faces count
  b.min.x() = 1.5;
  EXPECT_FALSE(overlaps(a, b));
  EXPECT_NEAR(squaredDistance(a, b), 0.25, 1e-15);
  EXPECT_TRUE(overlaps(inflated(a, 0.5), b));
  EXPECT_NEAR(squaredDistance(a, Vector3d(2, 3, 0.5)), 1.0 + 4.0, 1e-15);
  EXPECT_EQ(squaredDistance(a, Vector3d(0.5, 0.5, 0.5)), 0.0);
  EXPECT_FALSE(overlaps(BoundingBox{}, a));  // empty box overlaps nothing
  const BoundingBox t = boxOf(Vector3d(1, -1, 0), Vector3d(0, 2, 3), Vector3d(-1, 0, 1));
  EXPECT_EQ(t.min, Vector3d(-1, -1, 0));
  EXPECT_EQ(t.max, Vector3d(1, 2, 3));
}

}  // namespace
}  // namespace drape::collision
