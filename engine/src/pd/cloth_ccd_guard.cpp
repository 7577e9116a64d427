#include "drape/pd/cloth_ccd_guard.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "drape/collision/aabb.h"
#include "drape/collision/ccd.h"
#include "drape/collision/distance.h"

namespace drape::pd {
namespace {

constexpr int kRebuildInterval = 32;  // refits between full rebuilds of the swept-box trees
constexpr int kMaxPasses = 1000;      // safety cap; every pass but the last rolls back at least one vertex
constexpr int kBlock = 256;           // primitives per block of the candidate gathering

struct Candidate {
  int first = 0;
  int second = 0;
  std::array<int, 4> ids{};
  bool operator<(const Candidate& o) const { return first != o.first ? first < o.first : second < o.second; }
};

BoundingBox sweptBox(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& x, const int* ids, int count, double r) {
  BoundingBox b;
  for (int k = 0; k < count; ++k) {
    b.extend(start.row(ids[k]).transpose());
    b.extend(x.row(ids[k]).transpose());
  }
  return collision::inflated(b, r);
}

}  // namespace

ClothCcdGuard::ClothCcdGuard(const Eigen::MatrixX3i& triangles, std::vector<std::pair<int, int>> edges,
                             std::vector<int> canonical, double tolerance)
    : m_triangles(triangles), m_edges(std::move(edges)), m_canonical(std::move(canonical)), m_tolerance(tolerance) {}

void ClothCcdGuard::gatherCandidates(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& x) {
  const int nt = static_cast<int>(m_triangles.rows());
  const int ne = static_cast<int>(m_edges.size());
  const int nv = static_cast<int>(start.rows());
  const double r = m_tolerance;
  std::vector<BoundingBox> triangleBoxes(nt), edgeBoxes(ne), vertexBoxes(nv);
  tbb::parallel_for(0, nt, [&](int f) {
    const int ids[3] = {m_triangles(f, 0), m_triangles(f, 1), m_triangles(f, 2)};
    triangleBoxes[f] = sweptBox(start, x, ids, 3, r);
  });
  tbb::parallel_for(0, ne, [&](int e) {
    const int ids[2] = {m_edges[e].first, m_edges[e].second};
    edgeBoxes[e] = sweptBox(start, x, ids, 2, r);
  });
  tbb::parallel_for(0, nv, [&](int v) { vertexBoxes[v] = sweptBox(start, x, &v, 1, 0.0); });
  if (m_refits < 0 || m_refits >= kRebuildInterval) {
    m_triangleTree.build(triangleBoxes);
    m_edgeTree.build(edgeBoxes);
    m_refits = 0;
  } else {
    m_triangleTree.refit(triangleBoxes);
    m_edgeTree.refit(edgeBoxes);
    ++m_refits;
  }
  // Gathered per block of primitives (each block's list sorted, blocks concatenated in order): the same sorted
  // list whatever the scheduling, without a global sort.
  const int blocks = std::max(1, (std::max(nv, ne) + kBlock - 1) / kBlock);
  std::vector<std::vector<Candidate>> vtBlocks(blocks), eeBlocks(blocks);
  tbb::parallel_for(0, blocks, [&](int blk) {
    auto& out = vtBlocks[blk];
    for (int v = blk * kBlock; v < std::min(nv, (blk + 1) * kBlock); ++v) {
      const int cv = m_canonical[v];
      m_triangleTree.forEachOverlap(vertexBoxes[v], [&](int f) {
        const int a = m_triangles(f, 0), b = m_triangles(f, 1), c = m_triangles(f, 2);
        if (m_canonical[a] == cv || m_canonical[b] == cv || m_canonical[c] == cv) return;
        out.push_back({v, f, {v, a, b, c}});
      });
    }
    std::sort(out.begin(), out.end());
    auto& edgesOut = eeBlocks[blk];
    for (int e = blk * kBlock; e < std::min(ne, (blk + 1) * kBlock); ++e) {
      const int p0 = m_edges[e].first, p1 = m_edges[e].second;
      const int c0 = m_canonical[p0], c1 = m_canonical[p1];
      m_edgeTree.forEachOverlap(edgeBoxes[e], [&](int g) {
        if (g <= e) return;
        const int q0 = m_edges[g].first, q1 = m_edges[g].second;
        const int d0 = m_canonical[q0], d1 = m_canonical[q1];
        if (c0 == d0 || c0 == d1 || c1 == d0 || c1 == d1) return;
        edgesOut.push_back({e, g, {p0, p1, q0, q1}});
      });
    }
    std::sort(edgesOut.begin(), edgesOut.end());
  });
  m_candidates.clear();
  m_keys.clear();
  m_vertexTriangleCount = 0;
  for (const auto& part : vtBlocks) m_vertexTriangleCount += static_cast<int>(part.size());
  for (const auto* list : {&vtBlocks, &eeBlocks})
    for (const auto& part : *list)
      for (const Candidate& c : part) {
        m_candidates.push_back(c.ids);
        m_keys.emplace_back(c.first, c.second);
      }
  m_gathered = x;
}

bool ClothCcdGuard::touches(int i, const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& x, double& t) const {
  const std::array<int, 4>& id = m_candidates[i];
  Eigen::Vector3d s[4], d[4];
  bool moving = false;
  for (int k = 0; k < 4; ++k) {
    s[k] = start.row(id[k]).transpose();
    d[k] = x.row(id[k]).transpose() - s[k];
    moving = moving || d[k].squaredNorm() > 0.0;
  }
  if (!moving) return false;  // nothing moved: the start is taken as free of contact
  // Conservative filter: the gap between the two primitives changes by at most the largest relative displacement
  // of a vertex of one against a vertex of the other (the closest points are convex combinations), so a pair
  // farther apart at the start than that plus the tolerance cannot touch (most pairs of a cloth moving as a whole).
  const bool vertexTriangle = i < m_vertexTriangleCount;
  const int split = vertexTriangle ? 1 : 2;
  double relative2 = 0.0;
  for (int k = 0; k < split; ++k)
    for (int l = split; l < 4; ++l) relative2 = std::max(relative2, (d[k] - d[l]).squaredNorm());
  const double gap2 = vertexTriangle ? collision::closestPointTriangle(s[0], s[1], s[2], s[3]).distanceSquared
                                     : collision::closestPointsEdgeEdge(s[0], s[1], s[2], s[3]).distanceSquared;
  const double reach = std::sqrt(relative2) + m_tolerance;
  if (gap2 > reach * reach) return false;
  collision::CcdOptions options;
  options.tolerance = m_tolerance;
  const collision::CcdResult r =
      vertexTriangle ? collision::vertexTriangleCcd(s[0], s[1], s[2], s[3], d[0], d[1], d[2], d[3], options)
                                : collision::edgeEdgeCcd(s[0], s[1], s[2], s[3], d[0], d[1], d[2], d[3], options);
  t = r.t;
  return r.hit;
}

void ClothCcdGuard::findContacts(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& x,
                                 std::vector<ClothCcdHit>& vertexTriangle, std::vector<ClothCcdHit>& edgeEdge) {
  gatherCandidates(start, x);
  const int n = static_cast<int>(m_candidates.size());
  std::vector<char> hit(n, 0);
  std::vector<double> toi(n, 1.0);
  tbb::parallel_for(0, n, [&](int i) { hit[i] = touches(i, start, x, toi[i]); });
  m_lastHits = hit;
  m_gatheredStart = start;
  vertexTriangle.clear();
  edgeEdge.clear();
  for (int i = 0; i < n; ++i) {
    if (!hit[i]) continue;
    auto& out = i < m_vertexTriangleCount ? vertexTriangle : edgeEdge;
    out.push_back({m_candidates[i], m_keys[i].first, m_keys[i].second, toi[i]});
  }
}

ClothGuardStats ClothCcdGuard::enforce(const Eigen::MatrixX3d& start, Eigen::MatrixX3d& x,
                                       const std::function<bool(int)>& movable,
                                       const std::vector<std::pair<int, int>>& exempt) {
  ClothGuardStats stats;
  // The candidates of the last findContacts() serve when x has not changed since (e.g. nothing was projected).
  const bool reuse = m_gathered.rows() == x.rows() && m_gathered == x && m_gatheredStart.rows() == start.rows() &&
                     m_gatheredStart == start && static_cast<int>(m_lastHits.size()) == static_cast<int>(m_candidates.size());
  if (!reuse) gatherCandidates(start, x);
  const int n = static_cast<int>(m_candidates.size());
  const int nv = static_cast<int>(x.rows());
  stats.vertexTriangleCandidates = m_vertexTriangleCount;
  stats.edgeEdgeCandidates = n - m_vertexTriangleCount;
  std::vector<char> hit(n, 0), rolled(nv, 0), movedNow(nv, 0);
  std::vector<int> toTest;
  toTest.reserve(n);
  for (int i = 0; i < n; ++i)
    if (i >= m_vertexTriangleCount || !std::binary_search(exempt.begin(), exempt.end(), m_keys[i])) toTest.push_back(i);
  std::vector<int> moved;
  for (int pass = 0; pass < kMaxPasses && !toTest.empty(); ++pass) {
    if (pass == 0 && reuse) {
      for (int i : toTest) hit[i] = m_lastHits[i];
    } else {
      tbb::parallel_for(0, static_cast<int>(toTest.size()), [&](int k) {
        double t = 1.0;
        hit[toTest[k]] = touches(toTest[k], start, x, t);
      });
    }
    stats.passes = pass + 1;
    if (pass == 0) stats.hits = static_cast<int>(std::count(hit.begin(), hit.end(), 1));
    // Roll back the movable vertices of every touching pair, in pair order (deterministic).
    moved.clear();
    for (int i : toTest) {
      if (!hit[i]) continue;
      for (int v : m_candidates[i]) {
        if (rolled[v] || !movable(v)) continue;
        rolled[v] = 1;
        if (x.row(v) == start.row(v)) continue;
        x.row(v) = start.row(v);
        moved.push_back(v);
      }
    }
    stats.rolledBack += static_cast<int>(moved.size());
    // Next pass: the pairs that hold a vertex moved in this one (the others kept their motion and their result).
    for (int v : moved) movedNow[v] = 1;
    toTest.clear();
    if (!moved.empty())
      for (int i = 0; i < n; ++i) {
        const std::array<int, 4>& id = m_candidates[i];
        if (!(movedNow[id[0]] || movedNow[id[1]] || movedNow[id[2]] || movedNow[id[3]])) continue;
        if (i < m_vertexTriangleCount && std::binary_search(exempt.begin(), exempt.end(), m_keys[i])) continue;
        toTest.push_back(i);
      }
    for (int v : moved) movedNow[v] = 0;
  }
  stats.remaining = static_cast<int>(std::count(hit.begin(), hit.end(), 1));
  m_lastHits.clear();
  return stats;
}

}  // namespace drape::pd
