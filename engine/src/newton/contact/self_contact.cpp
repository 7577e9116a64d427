// Candidate pairs from collision::SelfProximity, exact penalty per pair through the stencil derivatives, per-pair
// results computed in parallel and scattered serially into the gradient and the dynamic Hessian blocks.
#include "drape/newton/contact/self_contact.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "drape/collision/self_intersection.h"

namespace drape::newton {
namespace {

// (key, item) pairs with keys in [0, n) as lists: key k's items are items[start[k]] .. items[start[k + 1] - 1].
void groupByKey(std::vector<std::pair<int, int>>& pairs, int n, std::vector<int>& start, std::vector<int>& items) {
  std::sort(pairs.begin(), pairs.end());
  start.assign(n + 1, 0);
  for (const auto& [key, item] : pairs) ++start[key + 1];
  for (int k = 0; k < n; ++k) start[k + 1] += start[k];
  items.clear();
  for (const auto& [key, item] : pairs) items.push_back(item);
}

}  // namespace

SelfContactEnergy::SelfContactEnergy(const Eigen::MatrixX3i& triangles, int vertexCount,
                                     const std::vector<std::pair<int, int>>& mergedVertices, ContactParameters params,
                                     double margin)
    : m_params(params),
      m_margin(margin > 0.0 ? margin : params.thickness),
      m_proximity(triangles, vertexCount, mergedVertices),
      m_merged(mergedVertices),
      m_excluded(vertexCount, 0) {
  const Eigen::MatrixX2i& edges = m_proximity.edges();
  std::vector<std::pair<int, int>> sortedEdges(edges.rows());  // uniqueEdges' order
  for (Eigen::Index e = 0; e < edges.rows(); ++e) sortedEdges[e] = {edges(e, 0), edges(e, 1)};
  std::vector<std::pair<int, int>> byVertex, byEdge;  // (vertex or edge, triangle)
  for (int f = 0; f < static_cast<int>(triangles.rows()); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(f, k), b = triangles(f, (k + 1) % 3);
      byVertex.emplace_back(a, f);
      const auto edge = std::lower_bound(sortedEdges.begin(), sortedEdges.end(), std::pair<int, int>(std::minmax(a, b)));
      byEdge.emplace_back(static_cast<int>(edge - sortedEdges.begin()), f);
    }
  groupByKey(byVertex, vertexCount, m_vertexTriangleStart, m_vertexTriangles);
  groupByKey(byEdge, static_cast<int>(sortedEdges.size()), m_edgeTriangleStart, m_edgeTriangles);
  // Triangles sharing an edge, across stitched seams too (an edge is known by its vertices' representatives), and
  // the pieces of cloth they make up.
  std::vector<std::pair<std::pair<int, int>, int>> byCanonicalEdge;
  for (int f = 0; f < static_cast<int>(triangles.rows()); ++f)
    for (int k = 0; k < 3; ++k)
      byCanonicalEdge.push_back({std::minmax(m_proximity.canonical(triangles(f, k)),
                                             m_proximity.canonical(triangles(f, (k + 1) % 3))),
                                 f});
  std::sort(byCanonicalEdge.begin(), byCanonicalEdge.end());
  std::vector<std::pair<int, int>> neighbours;
  for (std::size_t i = 0, j = 0; i < byCanonicalEdge.size(); i = j) {
    while (j < byCanonicalEdge.size() && byCanonicalEdge[j].first == byCanonicalEdge[i].first) ++j;
    for (std::size_t a = i; a < j; ++a)
      for (std::size_t b = i; b < j; ++b)
        if (a != b) neighbours.emplace_back(byCanonicalEdge[a].second, byCanonicalEdge[b].second);
  }
  groupByKey(neighbours, static_cast<int>(triangles.rows()), m_neighbourStart, m_neighbours);
  m_piece = components(std::vector<char>(triangles.rows(), 1));
}

std::vector<int> SelfContactEnergy::components(const std::vector<char>& included) const {
  std::vector<int> component(included.size(), -1);
  std::vector<int> stack;
  int count = 0;
  for (int seed = 0; seed < static_cast<int>(included.size()); ++seed) {
    if (!included[seed] || component[seed] >= 0) continue;
    component[seed] = count;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int i = m_neighbourStart[f]; i < m_neighbourStart[f + 1]; ++i) {
        const int g = m_neighbours[i];
        if (included[g] && component[g] < 0) {
          component[g] = count;
          stack.push_back(g);
        }
      }
    }
    ++count;
  }
  return component;
}

void SelfContactEnergy::excludeAroundCrossings() {
  std::fill(m_excluded.begin(), m_excluded.end(), 0);
  if (m_crossings.empty()) return;
  const auto& tris = m_proximity.triangles();
  const int faces = static_cast<int>(tris.rows());
  std::vector<char> free(faces, 1);
  for (const auto& [t, u] : m_crossings) free[t] = free[u] = 0;
  // Cut along its crossing triangles, a piece falls into sides; the one with the most triangles stays in contact.
  const std::vector<int> side = components(free);
  const int sides = 1 + *std::max_element(side.begin(), side.end());
  std::vector<int> size(std::max(sides, 0), 0);
  for (int f = 0; f < faces; ++f)
    if (side[f] >= 0) ++size[side[f]];
  std::vector<int> largest(1 + *std::max_element(m_piece.begin(), m_piece.end()), -1);
  for (int f = 0; f < faces; ++f) {
    if (side[f] < 0) continue;
    int& best = largest[m_piece[f]];
    if (best < 0 || size[side[f]] > size[best]) best = side[f];
  }
  for (int f = 0; f < faces; ++f)
    if (side[f] < 0 || side[f] != largest[m_piece[f]])
      for (int k = 0; k < 3; ++k) m_excluded[tris(f, k)] = 1;
}

void SelfContactEnergy::beginStep(const StepContext& ctx) {
  std::lock_guard lock(m_mutex);
  const Eigen::VectorXd& x = *ctx.previousPositions;
  const int queriesBefore = m_queries;
  ensureCandidates(x);
  const bool sameCandidates = m_crossingsAtQuery == queriesBefore && m_queries == queriesBefore;
  const auto& tris = m_proximity.triangles();
  m_crossings = sameCandidates ? crossingsNearCandidates(x) : collision::selfIntersectingPairs(x, tris, m_merged);
  m_crossingsAtQuery = m_queries;
  excludeAroundCrossings();
}

std::vector<std::pair<int, int>> SelfContactEnergy::crossingsNearCandidates(const Eigen::VectorXd& x) const {
  std::vector<std::pair<int, int>> pairs = m_crossings;
  auto addAll = [&](const std::vector<int>& start, const std::vector<int>& items, int key, int other) {
    for (int i = start[key]; i < start[key + 1]; ++i)
      if (items[i] != other) pairs.emplace_back(std::minmax(items[i], other));
  };
  for (const collision::VertexTrianglePair& p : m_vertexTriangle)
    addAll(m_vertexTriangleStart, m_vertexTriangles, p.vertex, p.triangle);
  for (const collision::EdgeEdgePair& p : m_edgeEdge)
    for (int i = m_edgeTriangleStart[p.second]; i < m_edgeTriangleStart[p.second + 1]; ++i)
      addAll(m_edgeTriangleStart, m_edgeTriangles, p.first, m_edgeTriangles[i]);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  const auto& tris = m_proximity.triangles();
  auto at = [&](int t, int k) -> Eigen::Vector3d { return x.segment<3>(3 * tris(t, k)); };
  std::vector<char> crossing(pairs.size(), 0);
  tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t i) {
    const auto [t, u] = pairs[i];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (m_proximity.canonical(tris(t, a)) == m_proximity.canonical(tris(u, b))) return;  // neighbours
    crossing[i] = collision::trianglesIntersect(at(t, 0), at(t, 1), at(t, 2), at(u, 0), at(u, 1), at(u, 2));
  });
  std::vector<std::pair<int, int>> out;
  for (std::size_t i = 0; i < pairs.size(); ++i)
    if (crossing[i]) out.push_back(pairs[i]);
  return out;
}

void SelfContactEnergy::ensureCandidates(const Eigen::VectorXd& x) const {
  if (m_reference.size() == x.size()) {
    const Eigen::VectorXd diff = x - m_reference;
    double maxMove2 = 0.0;
    for (Eigen::Index v = 0; v < diff.size() / 3; ++v)
      maxMove2 = std::max(maxMove2, diff.segment<3>(3 * v).squaredNorm());
    // Two primitives each moving at most margin/2 close a gap by at most margin.
    if (2.0 * std::sqrt(maxMove2) <= m_margin) return;
  }
  m_proximity.findPairs(x, m_params.thickness + m_margin, m_vertexTriangle, m_edgeEdge);
  m_reference = x;
  ++m_queries;
}

std::vector<SelfContactEnergy::Evaluated> SelfContactEnergy::evaluate(const Eigen::VectorXd& x,
                                                                      bool withHessian) const {
  ensureCandidates(x);
  const int vt = static_cast<int>(m_vertexTriangle.size());
  const int total = vt + static_cast<int>(m_edgeEdge.size());
  std::vector<Evaluated> all(total);
  std::vector<char> active(total, 0);
  const auto& tris = m_proximity.triangles();
  const auto& edges = m_proximity.edges();
  auto at = [&](int v) -> Eigen::Vector3d { return x.segment<3>(3 * v); };
  tbb::parallel_for(0, total, [&](int k) {
    Evaluated& e = all[k];
    if (k < vt) {
      const auto& p = m_vertexTriangle[k];
      e.vertices = {p.vertex, tris(p.triangle, 0), tris(p.triangle, 1), tris(p.triangle, 2)};
    } else {
      const auto& p = m_edgeEdge[k - vt];
      e.vertices = {edges(p.first, 0), edges(p.first, 1), edges(p.second, 0), edges(p.second, 1)};
    }
    for (int v : e.vertices)
      if (m_excluded[v]) return;  // on a triangle that crossed another at the step's start
    if (k < vt)
      e.distance = collision::pointTriangleSquaredDistance(at(e.vertices[0]), at(e.vertices[1]), at(e.vertices[2]),
                                                           at(e.vertices[3]));
    else
      e.distance = collision::edgeEdgeSquaredDistance(at(e.vertices[0]), at(e.vertices[1]), at(e.vertices[2]),
                                                      at(e.vertices[3]));
    active[k] = penaltyFromSquaredDistance(e.distance, m_params.stiffness, m_params.thickness,
                                           withHessian && m_params.projectHessian, e.energy, e.gradient, e.hessian);
  });
  std::vector<Evaluated> out;
  for (int k = 0; k < total; ++k) {
    if (active[k]) out.push_back(std::move(all[k]));
  }
  return out;
}

double SelfContactEnergy::value(const Eigen::VectorXd& x) const {
  std::lock_guard lock(m_mutex);
  double e = 0.0;
  for (const Evaluated& p : evaluate(x, false)) e += p.energy;
  return e;
}

void SelfContactEnergy::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  std::lock_guard lock(m_mutex);
  for (const Evaluated& p : evaluate(x, false)) {
    for (int i = 0; i < 4; ++i) g.segment<3>(3 * p.vertices[i]) += p.gradient.segment<3>(3 * i);
  }
}

void SelfContactEnergy::addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const {
  std::lock_guard lock(m_mutex);
  for (const Evaluated& p : evaluate(x, true)) {
    for (int i = 0; i < 4; ++i) {
      for (int j = i; j < 4; ++j) {
        const int vi = p.vertices[i];
        const int vj = p.vertices[j];
        const Eigen::Matrix3d b = p.hessian.block<3, 3>(3 * i, 3 * j);
        if (vi == vj) {
          // The same vertex twice cannot happen for non-adjacent pairs, but keep the sum exact if it does.
          h.addDynamicBlock(vi, vi, i == j ? b : Eigen::Matrix3d(b + b.transpose()));
        } else {
          h.addDynamicBlock(vi, vj, b);
        }
      }
    }
  }
}

std::vector<collision::ContactStencil> SelfContactEnergy::contacts(const Eigen::VectorXd& x) const {
  std::lock_guard lock(m_mutex);
  std::vector<collision::ContactStencil> out;
  for (const Evaluated& p : evaluate(x, false)) {
    collision::ContactStencil s;
    s.vertices = p.vertices;
    s.count = 4;
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) {
      s.weights[i] = p.distance.weights[i];
      r += s.weights[i] * x.segment<3>(3 * p.vertices[i]);
    }
    s.distance = r.norm();
    s.normal = r / s.distance;
    out.push_back(s);
  }
  return out;
}

}  // namespace drape::newton
