#include "drape/pd/cloth_collision.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "drape/collision/aabb.h"
#include "drape/collision/distance.h"
#include "drape/collision/contact_merged_vertices.h"
#include "drape/core/disjoint_sets.h"

namespace drape::pd {
namespace {

constexpr int kRebuildInterval = 32;       // refits between full rebuilds of the swept-box tree
constexpr double kResolveFraction = 0.75;  // resolve() pushes pairs closer than this x thickness to it
// Barycentric slack of the prism test at the step start: a vertex near a triangle's edge is sided with both
// triangles of the edge, so a crossing from one prism into the next within a step is still seen as one.
constexpr double kPrismSlack = 0.25;

// Barycentric coordinates (of a, b, c) of the projection of p onto the plane of (a, b, c); false when degenerate.
bool planeBarycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                      const Eigen::Vector3d& c, Eigen::Vector3d& bary) {
  const Eigen::Vector3d e0 = b - a, e1 = c - a, d = p - a;
  const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1);
  const double det = d00 * d11 - d01 * d01;
  if (!(det > 0.0)) return false;
  const double d20 = d.dot(e0), d21 = d.dot(e1);
  const double u = (d11 * d20 - d01 * d21) / det;
  const double w = (d00 * d21 - d01 * d20) / det;
  bary = Eigen::Vector3d(1.0 - u - w, u, w);
  return true;
}

std::uint64_t pairKey(int vertex, int triangle, int triangleCount) {
  return static_cast<std::uint64_t>(vertex) * static_cast<std::uint64_t>(triangleCount) +
         static_cast<std::uint64_t>(triangle);
}

}  // namespace

ClothContacts::ClothContacts(const Eigen::MatrixX3i& triangles, int vertexCount,
                             const std::vector<std::pair<int, int>>& stitches, std::vector<int> dofOfVertex,
                             const ClothContactOptions& options, const std::vector<model::EdgeStitch>& edgeStitches)
    : m_triangles(triangles), m_dofOfVertex(std::move(dofOfVertex)), m_options(options) {
  m_canonical.resize(vertexCount);
  std::iota(m_canonical.begin(), m_canonical.end(), 0);
  for (const auto& [a, b] : collision::contactMergedVertices(stitches, edgeStitches)) {
    if (a < 0 || b < 0 || a >= vertexCount || b >= vertexCount) continue;
    const int ra = findRoot(m_canonical, a), rb = findRoot(m_canonical, b);
    if (ra != rb) m_canonical[std::max(ra, rb)] = std::min(ra, rb);
  }
  for (int v = 0; v < vertexCount; ++v) m_canonical[v] = findRoot(m_canonical, v);
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * m_triangles.rows());
  for (int f = 0; f < m_triangles.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = std::min(m_triangles(f, k), m_triangles(f, (k + 1) % 3));
      const int b = std::max(m_triangles(f, k), m_triangles(f, (k + 1) % 3));
      keys.push_back(pairKey(a, b, vertexCount));
    }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  m_edges.reserve(keys.size());
  for (std::uint64_t k : keys)
    m_edges.emplace_back(static_cast<int>(k / static_cast<std::uint64_t>(vertexCount)),
                         static_cast<int>(k % static_cast<std::uint64_t>(vertexCount)));
  m_guard = std::make_unique<ClothCcdGuard>(m_triangles, m_edges, m_canonical);
}

ClothContacts::~ClothContacts() = default;

int ClothContacts::resolveEdges(Eigen::MatrixX3d& x, const std::function<double(int)>& inverseMass,
                                double goal) const {
  const double reach = m_options.thickness + m_options.margin;
  int moved = 0;
  for (const EdgePair& ep : m_edgePairs) {
    const auto& id = ep.ids;
    const Eigen::Vector3d p0 = x.row(id[0]).transpose(), p1 = x.row(id[1]).transpose();
    const Eigen::Vector3d q0 = x.row(id[2]).transpose(), q1 = x.row(id[3]).transpose();
    const Eigen::Vector3d cross = (p1 - p0).cross(q1 - q0);
    const double len = cross.norm();
    if (!(len > 0.0)) continue;
    const collision::EdgeEdgeResult cp = collision::closestPointsEdgeEdge(p0, p1, q0, q1);
    if (cp.distanceSquared >= reach * reach) continue;  // far apart now: left to the guard
    // Unit normal of the two edge lines, oriented so that q is in front of p as at the start.
    const Eigen::Vector3d n = ep.side * cross / len;
    const Eigen::Vector3d gap = (q0 + cp.t * (q1 - q0)) - (p0 + cp.s * (p1 - p0));
    const double height = gap.dot(n);
    if (height >= goal) continue;
    const double c[4] = {-(1.0 - cp.s), -cp.s, 1.0 - cp.t, cp.t};  // gradient of height along n per vertex
    double w[4], denom = 0.0;
    for (int k = 0; k < 4; ++k) {
      w[k] = inverseMass(id[k]);
      denom += w[k] * c[k] * c[k];
    }
    if (!(denom > 0.0)) continue;
    const double s = (goal - height) / denom;
    for (int k = 0; k < 4; ++k) x.row(id[k]) += (w[k] * c[k] * s) * n.transpose();
    ++moved;
  }
  return moved;
}

bool ClothContacts::adjacent(int vertex, int triangle) const {
  const int cv = m_canonical[vertex];
  for (int k = 0; k < 3; ++k)
    if (m_canonical[m_triangles(triangle, k)] == cv) return true;
  return false;
}

void ClothContacts::beginStep(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& predicted) {
  const int nt = static_cast<int>(m_triangles.rows());
  const int nv = static_cast<int>(start.rows());
  const double radius = m_options.thickness + m_options.margin;
  std::vector<BoundingBox> boxes(nt);
  tbb::parallel_for(0, nt, [&](int f) {
    BoundingBox b;
    for (int k = 0; k < 3; ++k) {
      b.extend(start.row(m_triangles(f, k)).transpose());
      b.extend(predicted.row(m_triangles(f, k)).transpose());
    }
    boxes[f] = collision::inflated(b, radius);
  });
  if (m_stepsSinceBuild < 0 || m_stepsSinceBuild >= kRebuildInterval) {
    m_tree.build(boxes);
    m_stepsSinceBuild = 0;
  } else {
    m_tree.refit(boxes);
    ++m_stepsSinceBuild;
  }
  const double reach = m_options.thickness + m_options.margin;
  // A start verified free of intersections by the last resolve() gives every side directly.
  m_startVerified = m_lastVerified && m_lastResolved.rows() == start.rows() && m_lastResolved == start;
  tbb::enumerable_thread_specific<std::vector<Pair>> local;
  tbb::parallel_for(0, nv, [&](int v) {
    if (m_dofOfVertex[v] < 0) return;
    const Eigen::Vector3d p0 = start.row(v).transpose();
    auto& out = local.local();
    m_tree.forEachOverlap(collision::boxOf(p0, predicted.row(v).transpose()), [&](int f) {
      if (adjacent(v, f)) return;
      const Eigen::Vector3d a = start.row(m_triangles(f, 0)).transpose();
      const Eigen::Vector3d b = start.row(m_triangles(f, 1)).transpose();
      const Eigen::Vector3d c = start.row(m_triangles(f, 2)).transpose();
      const Eigen::Vector3d n = (b - a).cross(c - a);
      const double area2 = n.norm();
      if (!(area2 > 0.0)) return;
      const double height = (p0 - a).dot(n) / area2;
      Eigen::Vector3d bary;
      const bool sided =
          std::abs(height) < reach && planeBarycentric(p0, a, b, c, bary) && bary.minCoeff() >= -kPrismSlack;
      double side = height > 0.0 ? 1.0 : -1.0;
      if (sided && !m_startVerified) {  // a side seen before in the prism is kept (read-only lookup)
        const auto it = m_sides.find(pairKey(v, f, nt));
        if (it != m_sides.end())
          side = it->second;
        else if (height == 0.0)
          return;  // in the plane: no side to keep
      } else if (height == 0.0) {
        return;
      }
      out.push_back({v, f, side, sided});
    });
  });
  m_pairs.clear();
  for (auto& part : local) m_pairs.insert(m_pairs.end(), part.begin(), part.end());
  // Sorted: the Gauss-Seidel projection of resolve() and the constraint order do not depend on the threads.
  std::sort(m_pairs.begin(), m_pairs.end(), [](const Pair& p, const Pair& q) {
    return p.vertex != q.vertex ? p.vertex < q.vertex : p.triangle < q.triangle;
  });
  m_sides.clear();
  for (const Pair& pr : m_pairs)
    if (pr.sided) m_sides.emplace(pairKey(pr.vertex, pr.triangle, nt), pr.side);
  m_edgePairs.clear();
}

void ClothContacts::addTouchingPair(const ClothCcdHit& hit, const Eigen::MatrixX3d& start, ClothResolveStats& stats) {
  const int nt = static_cast<int>(m_triangles.rows());
  const int v = hit.first, f = hit.second;
  if (m_dofOfVertex[v] < 0) return;  // a pinned vertex is never constrained (the guard handles its triangles)
  const auto it = std::lower_bound(m_pairs.begin(), m_pairs.end(), std::make_pair(v, f),
                                   [](const Pair& p, const std::pair<int, int>& k) {
                                     return p.vertex != k.first ? p.vertex < k.first : p.triangle < k.second;
                                   });
  const bool known = it != m_pairs.end() && it->vertex == v && it->triangle == f;
  if (known && it->sided) return;
  double side = 0.0;
  const auto remembered = m_sides.find(pairKey(v, f, nt));
  if (!m_startVerified && remembered != m_sides.end()) {
    side = remembered->second;
  } else {
    const Eigen::Vector3d p = start.row(v).transpose();
    const Eigen::Vector3d a = start.row(m_triangles(f, 0)).transpose();
    const Eigen::Vector3d b = start.row(m_triangles(f, 1)).transpose();
    const Eigen::Vector3d c = start.row(m_triangles(f, 2)).transpose();
    const double height = (p - a).dot((b - a).cross(c - a));
    if (height == 0.0) return;
    side = height > 0.0 ? 1.0 : -1.0;
  }
  ++stats.ccdCrossings;
  m_sides[pairKey(v, f, nt)] = side;
  if (known) {
    it->sided = true;
    it->side = side;
  } else {
    m_pairs.insert(it, Pair{v, f, side, true});
  }
}

ClothResolveStats ClothContacts::resolve(const Eigen::MatrixX3d& start, Eigen::MatrixX3d& x,
                                         const std::function<double(int)>& inverseMass, int maxSweeps) {
  ClothResolveStats stats;
  const double goal = kResolveFraction * m_options.thickness;
  const double deepest = m_options.thickness + m_options.margin;  // deeper "crossings" are not ours to undo
  // Pairs touching during the step (CCD over start -> x, own broad phase): vertex-triangle pairs become sided
  // pairs with their start side, edge-edge pairs are projected back to their start side.
  std::vector<ClothCcdHit> vertexTriangle, edgeEdge;
  m_guard->findContacts(start, x, vertexTriangle, edgeEdge);
  for (const ClothCcdHit& hit : vertexTriangle) addTouchingPair(hit, start, stats);
  m_edgePairs.clear();
  for (const ClothCcdHit& hit : edgeEdge) {
    const auto& id = hit.ids;
    const Eigen::Vector3d p0 = start.row(id[0]).transpose(), p1 = start.row(id[1]).transpose();
    const Eigen::Vector3d q0 = start.row(id[2]).transpose(), q1 = start.row(id[3]).transpose();
    const double vol = (q0 - p0).dot((p1 - p0).cross(q1 - q0));
    if (vol != 0.0) m_edgePairs.push_back({id, vol > 0.0 ? 1.0 : -1.0});
  }
  stats.edgeCrossings = static_cast<int>(edgeEdge.size());
  for (int sweep = 0; sweep < maxSweeps; ++sweep) {
    int violations = 0, crossed = 0;
    for (const Pair& pr : m_pairs) {
      if (!pr.sided) continue;
      const int iv = pr.vertex;
      const int ia = m_triangles(pr.triangle, 0), ib = m_triangles(pr.triangle, 1), ic = m_triangles(pr.triangle, 2);
      const Eigen::Vector3d p = x.row(iv).transpose();
      const Eigen::Vector3d a = x.row(ia).transpose(), b = x.row(ib).transpose(), c = x.row(ic).transpose();
      const Eigen::Vector3d cross = (b - a).cross(c - a);
      const double area2 = cross.norm();
      if (!(area2 > 0.0)) continue;
      const Eigen::Vector3d n = pr.side * cross / area2;
      const double height = (p - a).dot(n);
      if (height >= goal || height < -deepest) continue;
      Eigen::Vector3d bary;
      if (!planeBarycentric(p, a, b, c, bary) || bary.minCoeff() < 0.0) continue;
      ++violations;
      crossed += height < 0.0;
      // Point-triangle distance constraint C = (p - sum bary_i x_i) . n - goal >= 0, projected with inverse
      // masses (position-based dynamics): dp = w_p s n, dx_i = -w_i bary_i s n, s = -C / (w_p + sum w_i bary_i^2).
      const double wp = inverseMass(iv);
      const double w[3] = {inverseMass(ia), inverseMass(ib), inverseMass(ic)};
      const double denom = wp + w[0] * bary[0] * bary[0] + w[1] * bary[1] * bary[1] + w[2] * bary[2] * bary[2];
      if (!(denom > 0.0)) continue;
      const double s = (goal - height) / denom;
      x.row(iv) += (wp * s) * n.transpose();
      const int tri[3] = {ia, ib, ic};
      for (int k = 0; k < 3; ++k) x.row(tri[k]) -= (w[k] * bary[k] * s) * n.transpose();
    }
    violations += resolveEdges(x, inverseMass, goal);
    if (sweep == 0) {
      stats.violations = violations;
      stats.crossed = crossed;
    }
    stats.sweeps = sweep + 1;
    if (violations == 0) break;
  }
  // The safety net: no vertex keeps a motion that touches another primitive, except, from a start not verified
  // free of intersections, a vertex going back through a triangle it is remembered to have crossed.
  std::vector<std::pair<int, int>> exempt;
  if (!m_startVerified)
    for (const Pair& pr : m_pairs)
      if (pr.sided && crossed(pr, start)) exempt.emplace_back(pr.vertex, pr.triangle);
  const ClothGuardStats guard =
      m_guard->enforce(start, x, [&](int v) { return inverseMass(v) > 0.0; }, exempt);
  stats.rolledBack = guard.rolledBack;
  stats.guardHits = guard.hits;
  stats.remaining = guard.remaining;
  m_lastResolved = x;
  m_lastVerified = guard.remaining == 0 && (m_startVerified || exempt.empty());
  return stats;
}

bool ClothContacts::crossed(const Pair& pr, const Eigen::MatrixX3d& x) const {
  const double deepest = m_options.thickness + m_options.margin;
  const Eigen::Vector3d p = x.row(pr.vertex).transpose();
  const Eigen::Vector3d a = x.row(m_triangles(pr.triangle, 0)).transpose();
  const Eigen::Vector3d b = x.row(m_triangles(pr.triangle, 1)).transpose();
  const Eigen::Vector3d c = x.row(m_triangles(pr.triangle, 2)).transpose();
  const Eigen::Vector3d cross = (b - a).cross(c - a);
  const double area2 = cross.norm();
  if (!(area2 > 0.0)) return false;
  const double height = (p - a).dot(pr.side * cross / area2);
  Eigen::Vector3d bary;
  return height < 0.0 && height >= -deepest && planeBarycentric(p, a, b, c, bary) && bary.minCoeff() >= 0.0;
}

int ClothContacts::crossedPairs(const Eigen::MatrixX3d& x) const {
  int count = 0;
  for (const Pair& pr : m_pairs) count += pr.sided && crossed(pr, x);
  return count;
}

ClothContactStats ClothContacts::addConstraints(const Eigen::MatrixX3d& xFree, const Eigen::MatrixX3d& current,
                                                ContactAccumulator& acc) const {
  const int np = static_cast<int>(m_pairs.size());
  const double thickness = m_options.thickness;
  std::vector<char> active(np, 0);
  std::vector<Eigen::Vector3d> target(np);
  tbb::parallel_for(0, np, [&](int i) {
    const Pair& pr = m_pairs[i];
    const Eigen::Vector3d x = xFree.row(m_dofOfVertex[pr.vertex]).transpose();
    const Eigen::Vector3d a = current.row(m_triangles(pr.triangle, 0)).transpose();
    const Eigen::Vector3d b = current.row(m_triangles(pr.triangle, 1)).transpose();
    const Eigen::Vector3d c = current.row(m_triangles(pr.triangle, 2)).transpose();
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double area2 = cross.norm();
    if (!(area2 > 0.0)) return;
    const Eigen::Vector3d n = pr.side * cross / area2;  // towards the vertex's starting side
    const double height = (x - a).dot(n);
    if (height >= thickness) return;
    const collision::PointTriangleResult cp = collision::closestPointTriangle(x, a, b, c);
    if (cp.region == collision::TriangleRegion::Face) {
      target[i] = x + (thickness - height) * n;
      active[i] = 1;
    } else if (height > 0.0) {
      const double d = std::sqrt(cp.distanceSquared);
      if (d >= thickness || d <= 0.0) return;
      target[i] = cp.closest + (thickness / d) * (x - cp.closest);
      active[i] = 1;
    }
  });
  ClothContactStats stats;
  for (int i = 0; i < np; ++i)
    if (active[i]) {
      acc.add(m_dofOfVertex[m_pairs[i].vertex], target[i], m_options.weight);
      ++stats.contacts;
    }
  return stats;
}

}  // namespace drape::pd
