// Vertex-triangle pairs: each vertex box (inflated by d) against the triangle tree. Edge-edge pairs: each edge
// box (inflated by d) against the edges of the edge tree's later leaves, so that each pair is met once. Exact
// distances decide; per-thread buffers merge.
#include "drape/collision/self_proximity.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>

#include "drape/collision/distance.h"

namespace drape::collision {
namespace {

Eigen::Vector3d vertexAt(const Eigen::VectorXd& x, int v) { return x.segment<3>(3 * v); }

template <class T>
void gather(tbb::enumerable_thread_specific<std::vector<T>>& local, std::vector<T>& out) {
  out.clear();
  for (auto& part : local) out.insert(out.end(), part.begin(), part.end());
  std::sort(out.begin(), out.end());
}

}  // namespace

Eigen::MatrixX2i uniqueEdges(const Eigen::MatrixX3i& triangles) {
  std::vector<std::pair<int, int>> all;
  all.reserve(3 * triangles.rows());
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(f, k);
      const int b = triangles(f, (k + 1) % 3);
      all.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  Eigen::MatrixX2i edges(all.size(), 2);
  for (std::size_t e = 0; e < all.size(); ++e) edges.row(e) << all[e].first, all[e].second;
  return edges;
}

SelfProximity::SelfProximity(const Eigen::MatrixX3i& triangles, int vertexCount,
                             const std::vector<std::pair<int, int>>& mergedVertices)
    : m_triangles(triangles), m_edges(uniqueEdges(triangles)), m_vertexCount(vertexCount) {
  // Union-find over the merged pairs; the representative is the smallest index of each group.
  m_canonical.resize(vertexCount);
  std::iota(m_canonical.begin(), m_canonical.end(), 0);
  auto find = [&](int v) {
    while (m_canonical[v] != v) v = m_canonical[v] = m_canonical[m_canonical[v]];
    return v;
  };
  for (const auto& [a, b] : mergedVertices) {
    const int ra = find(a);
    const int rb = find(b);
    if (ra != rb) m_canonical[std::max(ra, rb)] = std::min(ra, rb);
  }
  for (int v = 0; v < vertexCount; ++v) m_canonical[v] = find(v);
}

bool SelfProximity::adjacent(const VertexTrianglePair& p) const {
  const int v = m_canonical[p.vertex];
  for (int k = 0; k < 3; ++k) {
    if (m_canonical[m_triangles(p.triangle, k)] == v) return true;
  }
  return false;
}

bool SelfProximity::adjacent(const EdgeEdgePair& p) const {
  for (int a = 0; a < 2; ++a) {
    for (int b = 0; b < 2; ++b) {
      if (m_canonical[m_edges(p.first, a)] == m_canonical[m_edges(p.second, b)]) return true;
    }
  }
  return false;
}

void SelfProximity::updateTrees(const Eigen::VectorXd& x) {
  const bool rebuild = m_refitsSinceBuild < 0 || m_refitsSinceBuild >= rebuildInterval;
  const int faces = static_cast<int>(m_triangles.rows());
  m_boxes.resize(faces);
  tbb::parallel_for(0, faces, [&](int f) {
    m_boxes[f] = boxOf(vertexAt(x, m_triangles(f, 0)), vertexAt(x, m_triangles(f, 1)), vertexAt(x, m_triangles(f, 2)));
  });
  rebuild ? m_triangleTree.build(m_boxes) : m_triangleTree.refit(m_boxes);
  const int edges = static_cast<int>(m_edges.rows());
  m_boxes.resize(edges);
  tbb::parallel_for(0, edges,
                    [&](int e) { m_boxes[e] = boxOf(vertexAt(x, m_edges(e, 0)), vertexAt(x, m_edges(e, 1))); });
  rebuild ? m_edgeTree.build(m_boxes) : m_edgeTree.refit(m_boxes);
  m_refitsSinceBuild = rebuild ? 0 : m_refitsSinceBuild + 1;
}

void SelfProximity::findPairs(const Eigen::VectorXd& x, double d, std::vector<VertexTrianglePair>& vertexTriangle,
                              std::vector<EdgeEdgePair>& edgeEdge) {
  updateTrees(x);
  const double d2 = d * d;

  tbb::enumerable_thread_specific<std::vector<VertexTrianglePair>> localVt;
  tbb::parallel_for(tbb::blocked_range<int>(0, m_vertexCount), [&](const tbb::blocked_range<int>& range) {
    auto& out = localVt.local();
    for (int v = range.begin(); v < range.end(); ++v) {
      const Eigen::Vector3d p = vertexAt(x, v);
      BoundingBox box;
      box.min = p.array() - d;
      box.max = p.array() + d;
      m_triangleTree.forEachOverlap(box, [&](int f) {
        const VertexTrianglePair pair{v, f};
        if (adjacent(pair)) return;
        const PointTriangleResult r = closestPointTriangle(p, vertexAt(x, m_triangles(f, 0)),
                                                           vertexAt(x, m_triangles(f, 1)), vertexAt(x, m_triangles(f, 2)));
        if (r.distanceSquared < d2) out.push_back(pair);
      });
    }
  });
  gather(localVt, vertexTriangle);

  tbb::enumerable_thread_specific<std::vector<EdgeEdgePair>> localEe;
  const int edgeCount = static_cast<int>(m_edges.rows());
  tbb::parallel_for(tbb::blocked_range<int>(0, edgeCount), [&](const tbb::blocked_range<int>& range) {
    auto& out = localEe.local();
    for (int leaf = range.begin(); leaf < range.end(); ++leaf) {
      const int e = m_edgeTree.primitiveAt(leaf);
      const Eigen::Vector3d p0 = vertexAt(x, m_edges(e, 0));
      const Eigen::Vector3d p1 = vertexAt(x, m_edges(e, 1));
      const BoundingBox box = inflated(boxOf(p0, p1), d);
      m_edgeTree.forEachOverlapAfter(box, leaf, [&](int other) {
        const EdgeEdgePair pair{std::min(e, other), std::max(e, other)};
        if (adjacent(pair)) return;
        const EdgeEdgeResult r = closestPointsEdgeEdge(p0, p1, vertexAt(x, m_edges(other, 0)), vertexAt(x, m_edges(other, 1)));
        if (r.distanceSquared < d2) out.push_back(pair);
      });
    }
  });
  gather(localEe, edgeEdge);
}

}  // namespace drape::collision
