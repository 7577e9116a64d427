// Per-vertex signed-distance penalty. Hessian of the signed distance d at a vertex whose closest feature spans E
// (a face, an edge or a point): with P = I - E (E^T E)^-1 E^T and n = grad d,
//   hess d = (P - n n^T) / d,
// zero for a face, the edge / point curvature otherwise (d signed: the same formula holds inside).
#include "drape/newton/contact/avatar_contact.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace drape::newton {

double insideStiffnessFactorFor(const ContactParameters& p, double largestStretch) {
  constexpr double kInsideOverStretch = 2.0;
  if (!(p.stiffness > 0.0)) return p.insideStiffnessFactor;
  return std::max(p.insideStiffnessFactor, kInsideOverStretch * largestStretch / p.stiffness);
}

double AvatarPenalty::energy(double distance) const {
  const double k = stiffness;
  const double t = thickness;
  if (distance >= 0.0) return 0.5 * k * (t - distance) * (t - distance);
  const double u = -distance;
  return 0.5 * k * t * t + k * t * u + 0.5 * k * insideStiffnessFactor * u * u;
}

double AvatarPenalty::force(double distance) const {
  const double k = stiffness;
  const double t = thickness;
  if (distance >= 0.0) return k * (t - distance);
  return k * t - k * insideStiffnessFactor * distance;
}

double AvatarPenalty::stiffnessAt(double distance) const {
  return distance >= 0.0 ? stiffness : stiffness * insideStiffnessFactor;
}

AvatarContactEnergy::AvatarContactEnergy(std::shared_ptr<const collision::AvatarCollider> collider, int vertexCount,
                                         ContactParameters params)
    : m_collider(std::move(collider)),
      m_vertexCount(vertexCount),
      m_params(params),
      m_penalty(params),
      m_startDistance(vertexCount, 0.0),
      m_startKind(vertexCount, StartKind::Far),
      m_nearby(vertexCount) {}

void AvatarContactEnergy::beginStep(const StepContext& ctx) {
  std::lock_guard lock(m_mutex);
  const Eigen::VectorXd& xn = *ctx.previousPositions;
  const bool propagate = m_startPositions.size() == xn.size();  // there was a last start
  const double radius = m_params.searchRadius;
  const double keep = m_params.thickness + kLowerBoundMargin;
  tbb::enumerable_thread_specific<int> queries(0);
  tbb::parallel_for(0, m_vertexCount, [&](int v) {
    const Eigen::Vector3d p = xn.segment<3>(3 * v);
    if (propagate && m_startKind[v] != StartKind::Far) {
      // 1-Lipschitz: the distance at p is at least the last start's (exact or itself a bound) minus the motion.
      const double lower = m_startDistance[v] - (p - m_startPositions.segment<3>(3 * v)).norm();
      if (lower > keep) {
        m_startDistance[v] = lower;
        m_startKind[v] = StartKind::Lower;
        return;
      }
    }
    ++queries.local();
    collision::SurfacePoint s;
    bool found = m_collider->closest(p, s, radius, m_nearby[v]);
    // Nothing within the radius: far outside, or deeper inside (ignored, see header). Outside, the exact distance
    // carries over to later steps as a bound, so that a vertex hanging away from the body is not queried again.
    if (!found && m_collider->closest(p, s) && s.signedDistance > 0.0) found = true;
    m_startDistance[v] = found ? s.signedDistance : radius;
    m_startKind[v] = found ? StartKind::Exact : StartKind::Far;
  });
  m_startPositions = xn;
  m_lastStartQueries = queries.combine(std::plus<int>());
  m_cachedX.resize(0);
}

void AvatarContactEnergy::update(const Eigen::VectorXd& x) const {
  if (m_cachedX.size() == x.size() && m_cachedX == x) return;
  const bool haveStart = m_startPositions.size() == x.size();
  const double th = m_params.thickness;
  const TriangleMesh& mesh = m_collider->mesh();
  tbb::enumerable_thread_specific<std::vector<Active>> local;
  tbb::enumerable_thread_specific<int> queries(0);
  tbb::parallel_for(tbb::blocked_range<int>(0, m_vertexCount), [&](const tbb::blocked_range<int>& range) {
    auto& out = local.local();
    for (int v = range.begin(); v < range.end(); ++v) {
      const Eigen::Vector3d p = x.segment<3>(3 * v);
      double bound = m_params.searchRadius;
      if (haveStart) {
        const double moved = (p - m_startPositions.segment<3>(3 * v)).norm();
        // 1-Lipschitz: d(p) >= d0 - moved > thickness. Not for a vertex deeper inside than the radius at the step
        // start (Far): it may have come within the radius since.
        if (m_startKind[v] != StartKind::Far && m_startDistance[v] - th > moved) continue;
        // Strict upper bound on the unsigned distance (1-Lipschitz), capped by the search radius; a start distance
        // that is only a lower bound gives none.
        if (m_startKind[v] == StartKind::Exact)
          bound = std::min(bound, (std::abs(m_startDistance[v]) + moved) * (1.0 + 1e-9) + 1e-12);
      }
      ++queries.local();
      collision::SurfacePoint s;
      if (!m_collider->closest(p, s, bound, m_nearby[v])) continue;  // one task per vertex: no race
      if (!(s.signedDistance < th)) continue;
      Active a;
      a.stencil.vertices[0] = v;
      a.stencil.weights[0] = 1.0;
      a.stencil.count = 1;
      a.stencil.distance = s.signedDistance;
      a.stencil.normal = s.normal;
      const auto corner = [&](int k) -> Eigen::Vector3d { return mesh.vertices.row(mesh.triangles(s.triangle, k)); };
      Eigen::Vector3d edge = Eigen::Vector3d::Zero();
      switch (s.region) {
        case collision::TriangleRegion::Face: break;
        case collision::TriangleRegion::EdgeAB: edge = corner(1) - corner(0); break;
        case collision::TriangleRegion::EdgeBC: edge = corner(2) - corner(1); break;
        case collision::TriangleRegion::EdgeCA: edge = corner(0) - corner(2); break;
        default: a.complement = Eigen::Matrix3d::Identity(); break;
      }
      if (edge.squaredNorm() > 0.0) {
        edge.normalize();
        a.complement = Eigen::Matrix3d::Identity() - edge * edge.transpose();
      }
      if (s.region != collision::TriangleRegion::Face) {
        // Keep |d| away from zero: the curvature of a point or edge distance blows up on the feature itself.
        const double dSafe = std::copysign(std::max(std::abs(s.signedDistance), 1e-2 * th), s.signedDistance);
        a.curvature = 1.0 / dSafe;
      }
      out.push_back(a);
    }
  });
  m_active.clear();
  for (auto& part : local) m_active.insert(m_active.end(), part.begin(), part.end());
  std::sort(m_active.begin(), m_active.end(),
            [](const Active& a, const Active& b) { return a.stencil.vertices[0] < b.stencil.vertices[0]; });
  m_stencils.clear();
  for (const Active& a : m_active) m_stencils.push_back(a.stencil);
  m_lastQueries = queries.combine(std::plus<int>());
  m_cachedX = x;
}

const std::vector<collision::ContactStencil>& AvatarContactEnergy::contacts(const Eigen::VectorXd& x) const {
  std::lock_guard lock(m_mutex);
  update(x);
  return m_stencils;
}

bool AvatarContactEnergy::satisfied(const Eigen::VectorXd& x) const {
  const double th = m_params.thickness;
  for (const collision::ContactStencil& c : contacts(x))
    if (c.distance < -th) return false;
  if (m_startPositions.size() != x.size()) return true;
  // A vertex outside at the step start that moved farther than its distance plus the search radius may have passed
  // through the contact band deeper inside than the queries look (1-Lipschitz): ask the collider itself.
  for (int v = 0; v < m_vertexCount; ++v) {
    if (m_startKind[v] == StartKind::Far || m_startDistance[v] < -th) continue;
    const Eigen::Vector3d p = x.segment<3>(3 * v);
    if ((p - m_startPositions.segment<3>(3 * v)).norm() <= m_startDistance[v] + m_params.searchRadius) continue;
    if (m_collider->signedDistance(p) < -th) return false;
  }
  return true;
}

double AvatarContactEnergy::value(const Eigen::VectorXd& x) const {
  std::lock_guard lock(m_mutex);
  update(x);
  double e = 0.0;
  for (const Active& a : m_active) e += m_penalty.energy(a.stencil.distance);
  return e;
}

void AvatarContactEnergy::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  std::lock_guard lock(m_mutex);
  update(x);
  for (const Active& a : m_active)
    g.segment<3>(3 * a.stencil.vertices[0]) -= m_penalty.force(a.stencil.distance) * a.stencil.normal;
}

void AvatarContactEnergy::addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const {
  std::lock_guard lock(m_mutex);
  update(x);
  for (const Active& a : m_active) {
    const Eigen::Vector3d& n = a.stencil.normal;
    // With f = dE/dg and s = d2E/dg2 (g = thickness - d): hess E = s n n^T - f hess d.
    double coefficient = -m_penalty.force(a.stencil.distance) * a.curvature;
    if (m_params.projectHessian) coefficient = std::max(coefficient, 0.0);
    Eigen::Matrix3d block = m_penalty.stiffnessAt(a.stencil.distance) * n * n.transpose();
    if (coefficient != 0.0) block += coefficient * (a.complement - n * n.transpose());
    h.addDynamicBlock(a.stencil.vertices[0], a.stencil.vertices[0], block);
  }
}

}  // namespace drape::newton
