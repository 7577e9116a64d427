#include "drape/collision/self_intersection.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>

#include "drape/collision/aabb.h"
#include "drape/collision/bvh.h"
#include "drape/core/disjoint_sets.h"

namespace drape::collision {
namespace {

// Every crossing pair (t, u), t < u: partners[t], increasing.
std::vector<std::vector<int>> crossingPartners(const Eigen::VectorXd& x, const Eigen::MatrixX3i& triangles,
                                               const std::vector<std::pair<int, int>>& joined) {
  const int nv = static_cast<int>(x.size() / 3);
  const int nt = static_cast<int>(triangles.rows());
  std::vector<std::vector<int>> partners(nt);
  if (nt < 2) return partners;
  std::vector<int> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [a, b] : joined) {
    if (a < 0 || b < 0 || a >= nv || b >= nv) continue;
    parent[findRoot(parent, a)] = findRoot(parent, b);
  }
  const auto p = [&](int tri, int k) -> Eigen::Vector3d { return x.segment<3>(3 * triangles(tri, k)); };
  Eigen::MatrixX3i corner(nt, 3);  // each triangle's vertices as their sets' roots
  std::vector<BoundingBox> boxes(nt);
  for (int t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) corner(t, k) = findRoot(parent, triangles(t, k));
    boxes[t] = boxOf(p(t, 0), p(t, 1), p(t, 2));
  }
  const Bvh tree(boxes);
  tbb::enumerable_thread_specific<std::vector<std::pair<int, int>>> found;
  tbb::parallel_for(tbb::blocked_range<int>(0, nt), [&](const tbb::blocked_range<int>& range) {
    auto& out = found.local();
    for (int leaf = range.begin(); leaf != range.end(); ++leaf) {
      const int t = tree.primitiveAt(leaf);
      tree.forEachOverlapAfter(boxes[t], leaf, [&](int u) {
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            if (corner(t, i) == corner(u, j)) return;  // neighbours (also across a sewn seam)
        if (trianglesIntersect(p(t, 0), p(t, 1), p(t, 2), p(u, 0), p(u, 1), p(u, 2)))
          out.emplace_back(std::minmax(t, u));
      });
    }
  });
  std::vector<std::pair<int, int>> pairs;
  for (const auto& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [t, u] : pairs) partners[t].push_back(u);
  return partners;
}

}  // namespace

SelfIntersections countSelfIntersections(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& triangles,
                                         const std::vector<std::pair<int, int>>& joined) {
  const Eigen::MatrixXd rowMajor = positions.transpose();  // x, y, z of each vertex in turn
  const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(rowMajor.data(), rowMajor.size());
  const std::vector<std::vector<int>> partners = crossingPartners(x, triangles, joined);
  SelfIntersections out;
  for (int t = 0; t < static_cast<int>(partners.size()); ++t) {
    if (partners[t].empty()) continue;
    if (out.firstTriangle < 0) {
      out.firstTriangle = t;
      out.secondTriangle = partners[t].front();
    }
    out.count += static_cast<int>(partners[t].size());
  }
  return out;
}

std::vector<std::pair<int, int>> selfIntersectingPairs(const Eigen::VectorXd& positions,
                                                       const Eigen::MatrixX3i& triangles,
                                                       const std::vector<std::pair<int, int>>& joined) {
  std::vector<std::pair<int, int>> out;
  const std::vector<std::vector<int>> partners = crossingPartners(positions, triangles, joined);
  for (int t = 0; t < static_cast<int>(partners.size()); ++t)
    for (int u : partners[t]) out.emplace_back(t, u);
  return out;
}

}  // namespace drape::collision
