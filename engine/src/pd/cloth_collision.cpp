#include "drape/pd/cloth_collision.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "drape/collision/aabb.h"
#include "drape/collision/ccd.h"
#include "drape/collision/distance.h"

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

int findRoot(std::vector<int>& parent, int v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

}  // namespace

ClothContacts::ClothContacts(const Eigen::MatrixX3i& triangles, int vertexCount,
                             const std::vector<std::pair<int, int>>& stitches, std::vector<int> dofOfVertex,
                             const ClothContactOptions& options)
    : m_triangles(triangles), m_dofOfVertex(std::move(dofOfVertex)), m_options(options) {
  m_canonical.resize(vertexCount);
  std::iota(m_canonical.begin(), m_canonical.end(), 0);
  for (const auto& [a, b] : stitches) {
    if (a < 0 || b < 0 || a >= vertexCount || b >= vertexCount) continue;
    const int ra = findRoot(m_canonical, a), rb = findRoot(m_canonical, b);
    if (ra != rb) m_canonical[std::max(ra, rb)] = std::min(ra, rb);
  }
  for (int v = 0; v < vertexCount; ++v) m_canonical[v] = findRoot(m_canonical, v);
  std::unordered_map<std::uint64_t, int> edgeId;
  m_vertexEdges.assign(vertexCount, {});
  m_triangleEdges.resize(m_triangles.rows());
  for (int f = 0; f < m_triangles.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = std::min(m_triangles(f, k), m_triangles(f, (k + 1) % 3));
      const int b = std::max(m_triangles(f, k), m_triangles(f, (k + 1) % 3));
      const auto [it, inserted] = edgeId.emplace(pairKey(a, b, vertexCount), static_cast<int>(m_edges.size()));
      if (inserted) {
        m_edges.emplace_back(a, b);
        m_vertexEdges[a].push_back(it->second);
        m_vertexEdges[b].push_back(it->second);
      }
      m_triangleEdges[f][k] = it->second;
    }
}

void ClothContacts::gatherEdgePairs(const Eigen::MatrixX3d& start) {
  const int ne = static_cast<int>(m_edges.size());
  std::vector<std::uint64_t> keys;
  for (const Pair& pr : m_pairs)
    for (int e1 : m_vertexEdges[pr.vertex])
      for (int e2 : m_triangleEdges[pr.triangle]) {
        const auto [a0, a1] = m_edges[e1];
        const auto [b0, b1] = m_edges[e2];
        const int ca0 = m_canonical[a0], ca1 = m_canonical[a1], cb0 = m_canonical[b0], cb1 = m_canonical[b1];
        if (ca0 == cb0 || ca0 == cb1 || ca1 == cb0 || ca1 == cb1) continue;
        keys.push_back(pairKey(std::min(e1, e2), std::max(e1, e2), ne));
      }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  m_edgePairs.clear();
  m_edgePairs.reserve(keys.size());
  for (std::uint64_t k : keys) {
    const int e1 = static_cast<int>(k / ne), e2 = static_cast<int>(k % ne);
    const Eigen::Vector3d p0 = start.row(m_edges[e1].first).transpose(), p1 = start.row(m_edges[e1].second).transpose();
    const Eigen::Vector3d q0 = start.row(m_edges[e2].first).transpose(), q1 = start.row(m_edges[e2].second).transpose();
    const double vol = (q0 - p0).dot((p1 - p0).cross(q1 - q0));
    if (vol == 0.0) continue;
    m_edgePairs.push_back({e1, e2, vol > 0.0 ? 1.0 : -1.0});
  }
}

int ClothContacts::resolveEdges(const Eigen::MatrixX3d& start, Eigen::MatrixX3d& x,
                                const std::function<double(int)>& inverseMass, double goal, bool firstSweep,
                                std::vector<char>& crossed) const {
  const int np = static_cast<int>(m_edgePairs.size());
  if (firstSweep) {  // which pairs went through each other during the step (parallel CCD)
    crossed.assign(np, 0);
    tbb::parallel_for(0, np, [&](int i) {
      const EdgePair& ep = m_edgePairs[i];
      const int id[4] = {m_edges[ep.first].first, m_edges[ep.first].second, m_edges[ep.second].first,
                         m_edges[ep.second].second};
      const Eigen::Vector3d p0 = x.row(id[0]).transpose(), p1 = x.row(id[1]).transpose();
      const Eigen::Vector3d q0 = x.row(id[2]).transpose(), q1 = x.row(id[3]).transpose();
      if (ep.side * (q0 - p0).dot((p1 - p0).cross(q1 - q0)) > 0.0) return;  // same side as at the start
      Eigen::Vector3d s0[4], d[4];
      for (int k = 0; k < 4; ++k) {
        s0[k] = start.row(id[k]).transpose();
        d[k] = x.row(id[k]).transpose() - s0[k];
      }
      if (collision::edgeEdgeCcd(s0[0], s0[1], s0[2], s0[3], d[0], d[1], d[2], d[3]).hit) crossed[i] = 1;
    });
  }
  int moved = 0;
  for (int i = 0; i < np; ++i) {
    if (!crossed[i]) continue;
    const EdgePair& ep = m_edgePairs[i];
    const int id[4] = {m_edges[ep.first].first, m_edges[ep.first].second, m_edges[ep.second].first,
                       m_edges[ep.second].second};
    const Eigen::Vector3d p0 = x.row(id[0]).transpose(), p1 = x.row(id[1]).transpose();
    const Eigen::Vector3d q0 = x.row(id[2]).transpose(), q1 = x.row(id[3]).transpose();
    const Eigen::Vector3d cross = (p1 - p0).cross(q1 - q0);
    const double len = cross.norm();
    if (!(len > 0.0)) continue;
    // Unit normal of the two edge lines, oriented so that q is in front of p as at the start.
    const Eigen::Vector3d n = ep.side * cross / len;
    const collision::EdgeEdgeResult cp = collision::closestPointsEdgeEdge(p0, p1, q0, q1);
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
      if (sided) {  // a side seen before in the prism is kept (read-only lookup, safe in parallel)
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
  m_sides.clear();
  for (const Pair& pr : m_pairs)
    if (pr.sided) m_sides.emplace(pairKey(pr.vertex, pr.triangle, nt), pr.side);
  gatherEdgePairs(start);
}

ClothResolveStats ClothContacts::resolve(const Eigen::MatrixX3d& start, Eigen::MatrixX3d& x,
                                         const std::function<double(int)>& inverseMass, int maxSweeps) {
  ClothResolveStats stats;
  const double goal = kResolveFraction * m_options.thickness;
  const double deepest = m_options.thickness + m_options.margin;  // deeper "crossings" are not ours to undo
  const int nt = static_cast<int>(m_triangles.rows());
  // Unsided pairs whose vertex ends in the prism on the other side: sided (with their start side) when CCD of the
  // vertex against the moving triangle finds that it went through the triangle during the step.
  const int np = static_cast<int>(m_pairs.size());
  std::vector<char> promote(np, 0);
  tbb::parallel_for(0, np, [&](int i) {
    const Pair& pr = m_pairs[i];
    if (pr.sided) return;
    const int iv = pr.vertex;
    const int t[3] = {m_triangles(pr.triangle, 0), m_triangles(pr.triangle, 1), m_triangles(pr.triangle, 2)};
    const Eigen::Vector3d p = x.row(iv).transpose();
    const Eigen::Vector3d a = x.row(t[0]).transpose(), b = x.row(t[1]).transpose(), c = x.row(t[2]).transpose();
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double area2 = cross.norm();
    if (!(area2 > 0.0)) return;
    const double height = (p - a).dot(pr.side * cross / area2);
    if (height >= 0.0 || height < -deepest) return;
    Eigen::Vector3d bary;
    if (!planeBarycentric(p, a, b, c, bary) || bary.minCoeff() < 0.0) return;
    Eigen::Vector3d s0[4], d[4];
    const int ids[4] = {iv, t[0], t[1], t[2]};
    for (int k = 0; k < 4; ++k) {
      s0[k] = start.row(ids[k]).transpose();
      d[k] = x.row(ids[k]).transpose() - s0[k];
    }
    if (collision::vertexTriangleCcd(s0[0], s0[1], s0[2], s0[3], d[0], d[1], d[2], d[3]).hit) promote[i] = 1;
  });
  for (int i = 0; i < np; ++i)
    if (promote[i]) {
      m_pairs[i].sided = true;
      m_sides[pairKey(m_pairs[i].vertex, m_pairs[i].triangle, nt)] = m_pairs[i].side;
      ++stats.ccdCrossings;
    }
  std::vector<char> edgeCrossed;
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
    violations += resolveEdges(start, x, inverseMass, goal, sweep == 0, edgeCrossed);
    if (sweep == 0) {
      stats.violations = violations;
      stats.crossed = crossed;
      stats.edgeCrossings = static_cast<int>(std::count(edgeCrossed.begin(), edgeCrossed.end(), 1));
    }
    stats.sweeps = sweep + 1;
    if (violations == 0) break;
  }
  stats.remaining = crossedPairs(x);
  return stats;
}

int ClothContacts::crossedPairs(const Eigen::MatrixX3d& x) const {
  const double deepest = m_options.thickness + m_options.margin;
  int count = 0;
  for (const Pair& pr : m_pairs) {
    if (!pr.sided) continue;
    const Eigen::Vector3d p = x.row(pr.vertex).transpose();
    const Eigen::Vector3d a = x.row(m_triangles(pr.triangle, 0)).transpose();
    const Eigen::Vector3d b = x.row(m_triangles(pr.triangle, 1)).transpose();
    const Eigen::Vector3d c = x.row(m_triangles(pr.triangle, 2)).transpose();
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double area2 = cross.norm();
    if (!(area2 > 0.0)) continue;
    const double height = (p - a).dot(pr.side * cross / area2);
    Eigen::Vector3d bary;
    if (height < 0.0 && height >= -deepest && planeBarycentric(p, a, b, c, bary) && bary.minCoeff() >= 0.0) ++count;
  }
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
