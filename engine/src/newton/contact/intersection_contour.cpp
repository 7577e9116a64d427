// Crossing segments by forward-mode automatic differentiation over the two triangles' 18 coordinates; a followed
// pull's candidate pairs from an LBVH over the triangles around the step's crossings, a held pull's gradient summed
// once at the step's start.
#include "drape/newton/contact/intersection_contour.h"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <unsupported/Eigen/AutoDiff>

#include "drape/collision/aabb.h"
#include "drape/collision/bvh.h"

namespace drape::newton {
namespace {

using Grad18 = Eigen::Matrix<double, 18, 1>;
using Ad = Eigen::AutoDiffScalar<Grad18>;
template <class S>
using Vec = Eigen::Matrix<S, 3, 1>;

// Rings of neighbouring triangles around the crossings whose pairs are followed through the step.
constexpr int kRings = 2;

// Points where the edges of triangle p pierce the interior of triangle q, appended to hits.
template <class S>
void edgeHits(const std::array<Vec<S>, 3>& p, const std::array<Vec<S>, 3>& q, std::vector<Vec<S>>& hits) {
  const Vec<S> n = (q[1] - q[0]).cross(q[2] - q[0]);
  std::array<S, 3> side;
  for (int i = 0; i < 3; ++i) side[i] = n.dot(p[i] - q[0]);
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    if (!((side[i] < 0.0 && side[j] > 0.0) || (side[i] > 0.0 && side[j] < 0.0))) continue;
    const Vec<S> hit = (side[j] * p[i] - side[i] * p[j]) / (side[j] - side[i]);
    bool inside = true;
    for (int k = 0; k < 3 && inside; ++k) inside = ((q[(k + 1) % 3] - q[k]).cross(hit - q[k])).dot(n) >= 0.0;
    if (inside) hits.push_back(hit);
  }
}

template <class S>
S segmentLength(const std::array<Vec<S>, 3>& a, const std::array<Vec<S>, 3>& b) {
  std::vector<Vec<S>> hits;
  edgeHits(a, b, hits);
  edgeHits(b, a, hits);
  if (hits.size() < 2) return S(0.0);
  // Two hits in general position; more only where an edge passes through a vertex: the farthest two.
  S best(0.0);
  for (size_t i = 0; i < hits.size(); ++i)
    for (size_t j = i + 1; j < hits.size(); ++j) {
      const S d = (hits[i] - hits[j]).norm();
      if (d > best) best = d;  // d = 0 never taken, where the norm has no derivative
    }
  return best;
}

}  // namespace

double crossingLength(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                      const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2,
                      Grad18* gradient) {
  const double length = segmentLength<double>({a0, a1, a2}, {b0, b1, b2});
  if (!gradient) return length;
  if (length == 0.0) {  // no crossing: a constant
    gradient->setZero();
    return 0.0;
  }
  const std::array<const Eigen::Vector3d*, 6> in{&a0, &a1, &a2, &b0, &b1, &b2};
  std::array<Vec<Ad>, 6> v;
  for (int i = 0; i < 6; ++i)
    for (int c = 0; c < 3; ++c) v[i](c) = Ad((*in[i])(c), 18, 3 * i + c);
  *gradient = segmentLength<Ad>({v[0], v[1], v[2]}, {v[3], v[4], v[5]}).derivatives();
  return length;
}

IntersectionContourEnergy::IntersectionContourEnergy(const SelfContactEnergy* self, double force, ContourPull pull)
    : m_self(self), m_force(force), m_pull(pull) {}

void IntersectionContourEnergy::beginStep(const StepContext& ctx) {
  m_candidates.clear();
  m_heldAt.resize(0);
  m_heldGradient.resize(0);
  const std::vector<std::pair<int, int>>& crossings = m_self->crossings();
  if (crossings.empty()) return;
  if (m_pull == ContourPull::HeldOverTheStep) {
    holdAt(crossings, *ctx.previousPositions);
  } else {
    followAround(crossings, *ctx.previousPositions);
  }
}

void IntersectionContourEnergy::holdAt(const std::vector<std::pair<int, int>>& crossings, const Eigen::VectorXd& x) {
  const Eigen::MatrixX3i& tris = m_self->triangles();
  const auto at = [&](int t, int k) -> Eigen::Vector3d { return x.segment<3>(3 * tris(t, k)); };
  m_heldAt = x;
  m_heldGradient = Eigen::VectorXd::Zero(x.size());
  for (const auto& [t, u] : crossings) {
    Grad18 gradient;
    crossingLength(at(t, 0), at(t, 1), at(t, 2), at(u, 0), at(u, 1), at(u, 2), &gradient);
    for (int k = 0; k < 3; ++k) {
      m_heldGradient.segment<3>(3 * tris(t, k)) += m_force * gradient.segment<3>(3 * k);
      m_heldGradient.segment<3>(3 * tris(u, k)) += m_force * gradient.segment<3>(9 + 3 * k);
    }
  }
}

void IntersectionContourEnergy::followAround(const std::vector<std::pair<int, int>>& crossings,
                                             const Eigen::VectorXd& x) {
  const Eigen::MatrixX3i& tris = m_self->triangles();
  const int nt = static_cast<int>(tris.rows());
  // The region: the crossing triangles and kRings rings of triangles around them (sharing a vertex).
  std::vector<char> inRegion(nt, 0), vertexIn(x.size() / 3, 0);
  for (const auto& [t, u] : crossings) inRegion[t] = inRegion[u] = 1;
  for (int ring = 0; ring < kRings; ++ring) {
    for (int t = 0; t < nt; ++t)
      if (inRegion[t])
        for (int k = 0; k < 3; ++k) vertexIn[tris(t, k)] = 1;
    for (int t = 0; t < nt; ++t)
      if (vertexIn[tris(t, 0)] || vertexIn[tris(t, 1)] || vertexIn[tris(t, 2)]) inRegion[t] = 1;
  }
  std::vector<int> region;
  for (int t = 0; t < nt; ++t)
    if (inRegion[t]) region.push_back(t);
  // Pairs whose boxes come within twice the contact thickness of each other at x_n: those the contour moves into
  // during a step (the self contact keeps every other pair at least a thickness apart).
  const double reach = 2.0 * m_self->parameters().thickness;
  std::vector<BoundingBox> boxes(region.size());
  for (size_t i = 0; i < region.size(); ++i) {
    const int t = region[i];
    boxes[i] = collision::inflated(
        collision::boxOf(x.segment<3>(3 * tris(t, 0)), x.segment<3>(3 * tris(t, 1)), x.segment<3>(3 * tris(t, 2))),
        0.5 * reach);
  }
  const collision::Bvh tree(boxes);
  for (size_t i = 0; i < region.size(); ++i) {
    const int t = region[i];
    tree.forEachOverlap(boxes[i], [&](int j) {
      const int u = region[j];
      if (u <= t) return;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          if (m_self->canonical(tris(t, a)) == m_self->canonical(tris(u, b))) return;
      m_candidates.emplace_back(t, u);
    });
  }
}

double IntersectionContourEnergy::value(const Eigen::VectorXd& x) const {
  if (m_heldGradient.size() > 0) return m_heldGradient.dot(x - m_heldAt);
  const Eigen::MatrixX3i& tris = m_self->triangles();
  const auto at = [&](int t, int k) -> Eigen::Vector3d { return x.segment<3>(3 * tris(t, k)); };
  std::vector<double> length(m_candidates.size(), 0.0);
  tbb::parallel_for(size_t(0), m_candidates.size(), [&](size_t i) {
    const auto [t, u] = m_candidates[i];
    length[i] = crossingLength(at(t, 0), at(t, 1), at(t, 2), at(u, 0), at(u, 1), at(u, 2));
  });
  double sum = 0.0;
  for (double l : length) sum += l;
  return m_force * sum;
}

void IntersectionContourEnergy::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  if (m_heldGradient.size() > 0) {
    g += m_heldGradient;
    return;
  }
  const Eigen::MatrixX3i& tris = m_self->triangles();
  const auto at = [&](int t, int k) -> Eigen::Vector3d { return x.segment<3>(3 * tris(t, k)); };
  std::vector<Grad18> gradient(m_candidates.size());
  tbb::parallel_for(size_t(0), m_candidates.size(), [&](size_t i) {
    const auto [t, u] = m_candidates[i];
    crossingLength(at(t, 0), at(t, 1), at(t, 2), at(u, 0), at(u, 1), at(u, 2), &gradient[i]);
  });
  for (size_t i = 0; i < m_candidates.size(); ++i) {
    const auto [t, u] = m_candidates[i];
    for (int k = 0; k < 3; ++k) {
      g.segment<3>(3 * tris(t, k)) += m_force * gradient[i].segment<3>(3 * k);
      g.segment<3>(3 * tris(u, k)) += m_force * gradient[i].segment<3>(9 + 3 * k);
    }
  }
}

}  // namespace drape::newton
