// LBVH queries against brute force: box overlaps and nearest primitive on random boxes, before and after a refit;
// self-proximity pair sets on a randomly crumpled, folded cloth against an all-pairs search.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "drape/collision/bvh.h"
#include "drape/collision/distance.h"
#include "drape/collision/self_proximity.h"

namespace drape::collision {
namespace {

using Eigen::Vector3d;

std::vector<BoundingBox> randomBoxes(std::mt19937& rng, int n, double size) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<BoundingBox> boxes(n);
  for (auto& b : boxes) {
    const Vector3d c(u(rng), u(rng), u(rng));
    const Vector3d h = size * Vector3d(u(rng), u(rng), u(rng));
    b.min = c - h;
    b.max = c + h;
  }
  return boxes;
}

// Every box moved by a random shift (a refit's input).
void shiftBoxes(std::mt19937& rng, std::vector<BoundingBox>& boxes) {
  std::normal_distribution<double> shift(0.0, 0.05);
  for (auto& b : boxes) {
    const Vector3d s(shift(rng), shift(rng), shift(rng));
    b.min += s;
    b.max += s;
  }
}

void expectOverlapsMatch(const Bvh& bvh, const std::vector<BoundingBox>& boxes, const BoundingBox& query) {
  std::set<int> found;
  bvh.forEachOverlap(query, [&](int i) { EXPECT_TRUE(found.insert(i).second) << "reported twice: " << i; });
  std::set<int> expected;
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i) {
    if (overlaps(boxes[i], query)) expected.insert(i);
  }
  EXPECT_EQ(found, expected);
}

TEST(CollisionBvhTest, OverlapQueriesMatchBruteForceBeforeAndAfterRefit) {
  std::mt19937 rng(3);
  for (int n : {0, 1, 2, 3, 17, 1000}) {
    std::vector<BoundingBox> boxes = randomBoxes(rng, n, 0.03);
    Bvh bvh(boxes);
    EXPECT_EQ(bvh.primitiveCount(), n);
    const auto queries = randomBoxes(rng, 50, 0.1);
    for (const auto& q : queries) expectOverlapsMatch(bvh, boxes, q);
    // Move every box and refit: the same queries must still be exact.
    shiftBoxes(rng, boxes);
    bvh.refit(boxes);
    for (const auto& q : queries) expectOverlapsMatch(bvh, boxes, q);
  }
}

TEST(CollisionBvhTest, DuplicateCentresStillFormAValidTree) {
  std::vector<BoundingBox> boxes(500);
  for (auto& b : boxes) {
    b.min = Vector3d::Zero();
    b.max = Vector3d::Ones();
  }
  Bvh bvh(boxes);
  int count = 0;
  bvh.forEachOverlap(boxes[0], [&](int) { ++count; });
  EXPECT_EQ(count, 500);
  EXPECT_LT(bvh.depth(), 20);  // ties split by index give a balanced tree
}

TEST(CollisionBvhTest, OverlapsAfterEachLeafFindEveryOverlappingPairOnce) {
  std::mt19937 rng(4);
  for (int n : {0, 1, 2, 3, 17, 800}) {
    std::vector<BoundingBox> boxes = randomBoxes(rng, n, 0.05);
    for (int round = 0; round < 2; ++round) {
      Bvh bvh(boxes);
      if (round == 1) {  // refitted to moved boxes
        shiftBoxes(rng, boxes);
        bvh.refit(boxes);
      }
      std::multiset<std::pair<int, int>> found;
      for (int leaf = 0; leaf < n; ++leaf) {
        const int a = bvh.primitiveAt(leaf);
        bvh.forEachOverlapAfter(boxes[a], leaf, [&](int b) { found.insert(std::minmax(a, b)); });
      }
      std::multiset<std::pair<int, int>> expected;
      for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b)
          if (overlaps(boxes[a], boxes[b])) expected.insert({a, b});
      if (n == 800) EXPECT_GT(expected.size(), 100u);
      EXPECT_EQ(found, expected);
    }
  }
}

TEST(CollisionBvhTest, NearestMatchesBruteForce) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  const auto boxes = randomBoxes(rng, 2000, 0.01);
  const Bvh bvh(boxes);
  for (int k = 0; k < 200; ++k) {
    const Vector3d p(u(rng), u(rng), u(rng));
    // Distance to a primitive = distance to its box centre (the box bounds it from below).
    auto dist2 = [&](int i) { return (boxes[i].center() - p).squaredNorm(); };
    double best = std::numeric_limits<double>::infinity();
    const int found = bvh.nearest(p, dist2, best);
    int expected = 0;
    for (int i = 1; i < 2000; ++i) {
      if (dist2(i) < dist2(expected)) expected = i;
    }
    EXPECT_EQ(found, expected);
    EXPECT_EQ(best, dist2(expected));
  }
}

// A folded grid: the sheet is bent into a U so that its two halves face each other at a small gap, with noise,
// giving many vertex-triangle and edge-edge proximities between non-adjacent elements.
struct Cloth {
  Eigen::MatrixX3i triangles;
  Eigen::VectorXd x;
};

Cloth foldedCloth(int n, std::mt19937& rng) {
  Cloth cloth;
  const double step = 1.0 / (n - 1);
  cloth.x.resize(3 * n * n);
  std::normal_distribution<double> noise(0.0, 0.15 * step);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double s = i * step;  // arc length along the fold direction
      const double gap = 1.5 * step;
      Vector3d p;
      if (s < 0.45) {
        p = Vector3d(s, j * step, 0.0);
      } else if (s > 0.55) {
        p = Vector3d(1.0 - s, j * step, gap);
      } else {
        const double angle = (s - 0.45) / 0.1 * 3.14159265358979;
        p = Vector3d(0.45 + 0.5 * gap * std::sin(angle), j * step, 0.5 * gap * (1 - std::cos(angle)));
      }
      cloth.x.segment<3>(3 * (i * n + j)) = p + Vector3d(noise(rng), noise(rng), noise(rng));
    }
  }
  cloth.triangles.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j + 1 < n; ++j) {
      const int v = i * n + j;
      cloth.triangles.row(f++) << v, v + n, v + 1;
      cloth.triangles.row(f++) << v + 1, v + n, v + n + 1;
    }
  }
  return cloth;
}

TEST(CollisionBvhTest, SelfProximityMatchesAllPairs) {
  std::mt19937 rng(9);
  for (int n : {12, 25}) {
    Cloth cloth = foldedCloth(n, rng);
    const int vertices = n * n;
    // Merge two far-apart vertices as if stitched: their pairs must disappear.
    SelfProximity proximity(cloth.triangles, vertices, {{0, vertices - 1}});
    const double d = 1.8 / (n - 1);
    for (int round = 0; round < 2; ++round) {
      std::vector<VertexTrianglePair> vt;
      std::vector<EdgeEdgePair> ee;
      proximity.findPairs(cloth.x, d, vt, ee);

      std::vector<VertexTrianglePair> vtExpected;
      auto at = [&](int v) -> Vector3d { return cloth.x.segment<3>(3 * v); };
      for (int v = 0; v < vertices; ++v) {
        for (int t = 0; t < cloth.triangles.rows(); ++t) {
          const VertexTrianglePair pair{v, t};
          if (proximity.adjacent(pair)) continue;
          const auto& tri = cloth.triangles;
          if (closestPointTriangle(at(v), at(tri(t, 0)), at(tri(t, 1)), at(tri(t, 2))).distanceSquared < d * d) {
            vtExpected.push_back(pair);
          }
        }
      }
      std::vector<EdgeEdgePair> eeExpected;
      const auto& edges = proximity.edges();
      for (int a = 0; a < edges.rows(); ++a) {
        for (int b = a + 1; b < edges.rows(); ++b) {
          const EdgeEdgePair pair{a, b};
          if (proximity.adjacent(pair)) continue;
          if (closestPointsEdgeEdge(at(edges(a, 0)), at(edges(a, 1)), at(edges(b, 0)), at(edges(b, 1)))
                  .distanceSquared < d * d) {
            eeExpected.push_back(pair);
          }
        }
      }
      EXPECT_GT(vtExpected.size(), 50u);  // the fold really produces proximities
      EXPECT_GT(eeExpected.size(), 50u);
      EXPECT_EQ(vt, vtExpected);
      EXPECT_EQ(ee, eeExpected);
      // Second round: move the cloth (refit path) and compare again.
      std::normal_distribution<double> move(0.0, 0.3 / (n - 1));
      for (int k = 0; k < cloth.x.size(); ++k) cloth.x[k] += move(rng);
    }
  }
}

TEST(CollisionBvhTest, MergedVerticesCountAsAdjacent) {
  Eigen::MatrixX3i tris(2, 3);
  tris << 0, 1, 2, 3, 4, 5;
  const SelfProximity p(tris, 6, {{2, 3}});
  EXPECT_TRUE(p.adjacent(VertexTrianglePair{3, 0}));
  EXPECT_TRUE(p.adjacent(VertexTrianglePair{2, 1}));
  EXPECT_FALSE(p.adjacent(VertexTrianglePair{4, 0}));
  EXPECT_EQ(uniqueEdges(tris).rows(), 6);
}

}  // namespace
}  // namespace drape::collision
