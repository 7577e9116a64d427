#include "drape/collision/self_intersection.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>

#include "drape/collision/aabb.h"
#include "drape/collision/bvh.h"
#include "drape/core/disjoint_sets.h"

namespace drape::collision {
namespace {

struct TriangleResult {
  int count = 0;
  int first = -1;  // the smallest partner index (larger than the triangle's own)
};

}  // namespace

SelfIntersections countSelfIntersections(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& triangles,
                                         const std::vector<std::pair<int, int>>& joined) {
  const int nv = static_cast<int>(positions.rows());
  const int nt = static_cast<int>(triangles.rows());
  SelfIntersections out;
  if (nt < 2) return out;
  std::vector<int> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [a, b] : joined) {
    if (a < 0 || b < 0 || a >= nv || b >= nv) continue;
    parent[findRoot(parent, a)] = findRoot(parent, b);
  }
  Eigen::MatrixX3i corner(nt, 3);  // each triangle's vertices as their sets' roots
  std::vector<BoundingBox> boxes(nt);
  for (int t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) corner(t, k) = findRoot(parent, triangles(t, k));
    boxes[t] = boxOf(positions.row(triangles(t, 0)).transpose(), positions.row(triangles(t, 1)).transpose(),
                     positions.row(triangles(t, 2)).transpose());
  }
  const Bvh tree(boxes);
  std::vector<TriangleResult> results(nt);
  tbb::parallel_for(tbb::blocked_range<int>(0, nt), [&](const tbb::blocked_range<int>& range) {
    for (int t = range.begin(); t != range.end(); ++t) {
      TriangleResult& r = results[t];
      tree.forEachOverlap(boxes[t], [&](int u) {
        if (u <= t) return;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            if (corner(t, i) == corner(u, j)) return;  // neighbours (also across a sewn seam)
        const auto p = [&](int tri, int k) -> Eigen::Vector3d { return positions.row(triangles(tri, k)).transpose(); };
        if (!trianglesIntersect(p(t, 0), p(t, 1), p(t, 2), p(u, 0), p(u, 1), p(u, 2))) return;
        ++r.count;
        if (r.first < 0 || u < r.first) r.first = u;
      });
    }
  });
  for (int t = 0; t < nt; ++t) {
    if (results[t].count == 0) continue;
    if (out.firstTriangle < 0) {
      out.firstTriangle = t;
      out.secondTriangle = results[t].first;
    }
    out.count += results[t].count;
  }
  return out;
}

}  // namespace drape::collision
