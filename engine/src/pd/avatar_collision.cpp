#include "drape/pd/avatar_collision.h"

#include <Eigen/Geometry>

#include <tbb/parallel_for.h>

#include "drape/collision/aabb.h"
#include "drape/collision/avatar_collider.h"
#include "drape/collision/ccd.h"
#include "drape/collision/distance.h"

namespace drape::pd {

AvatarContacts::AvatarContacts(std::shared_ptr<const collision::AvatarCollider> collider,
                               const AvatarContactOptions& options)
    : m_collider(std::move(collider)), m_options(options) {
  const TriangleMesh& mesh = m_collider->mesh();
  m_faceNormals.resize(mesh.triangleCount());
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    m_faceNormals[f] = n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
  }
}

void AvatarContacts::beginStep(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& predicted,
                               const std::vector<int>& freeVertices) {
  const int nf = static_cast<int>(freeVertices.size());
  const double reach = m_options.thickness + m_options.margin;
  // Beyond the candidates' reach, distances are bounded up to this much more (a query radius: larger costs more).
  constexpr double kBoundSlack = 0.05;
  std::vector<char> near(nf, 0);
  m_bound.assign(nf, 0.0f);
  m_freeStart.resize(nf, 3);
  tbb::parallel_for(0, nf, [&](int d) {
    const int v = freeVertices[d];
    m_freeStart.row(d) = start.row(v);
    const double travel = (predicted.row(v) - start.row(v)).norm();
    const double watch = reach + 2.0 * travel;
    collision::SurfacePoint sp;
    const bool found = m_collider->closest(start.row(v).transpose(), sp, watch + kBoundSlack);
    near[d] = found && sp.signedDistance < watch;
    // Rounded down so that the bound stays a lower bound in single precision.
    m_bound[d] = static_cast<float>((found ? std::max(sp.signedDistance, 0.0) : watch + kBoundSlack) * (1.0 - 1e-6));
  });
  if (m_options.holdTargets) {
    m_held.resize(nf);
    m_heldKind.assign(nf, 0);
  }
  m_candidates.clear();
  for (int d = 0; d < nf; ++d)
    if (near[d]) m_candidates.push_back(d);
}

int AvatarContacts::firstCrossing(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) const {
  const TriangleMesh& mesh = m_collider->mesh();
  const Eigen::Vector3d dp = p1 - p0;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  int best = -1;
  double bestT = 2.0;
  m_collider->tree().forEachOverlap(collision::inflated(collision::boxOf(p0, p1), 1e-9), [&](int f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0));
    const Eigen::Vector3d& n = m_faceNormals[f];
    // Crossed from the outer side: start in front of the plane, end behind it.
    if ((p0 - a).dot(n) <= 0.0 || (p1 - a).dot(n) > 0.0) return;
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2));
    const collision::CcdResult r = collision::vertexTriangleCcd(p0, a, b, c, dp, zero, zero, zero);
    if (r.hit && r.t < bestT) {
      bestT = r.t;
      best = f;
    }
  });
  return best;
}

char AvatarContacts::constrain(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, Eigen::Vector3d& target) const {
  const double thickness = m_options.thickness;
  const double reach = thickness + m_options.margin;
  const double mu = m_options.friction;
  collision::SurfacePoint sp;
  const bool near = m_collider->closest(p1, sp, reach);
  const double travel = (p1 - p0).norm();
  // A segment shorter than the end's distance to the surface cannot have crossed it.
  const bool mayCross = m_options.ccd && travel > 0.0 && (near ? sp.signedDistance < travel : travel >= reach);
  const int f = mayCross ? firstCrossing(p0, p1) : -1;
  Eigen::Vector3d n;
  char kind = 0;
  if (f >= 0) {
    const TriangleMesh& mesh = m_collider->mesh();
    const collision::PointTriangleResult cp = collision::closestPointTriangle(
        p1, mesh.vertices.row(mesh.triangles(f, 0)).transpose(), mesh.vertices.row(mesh.triangles(f, 1)).transpose(),
        mesh.vertices.row(mesh.triangles(f, 2)).transpose());
    n = m_faceNormals[f];
    target = cp.closest + thickness * n;
    kind = 2;
  } else if (near && sp.signedDistance < thickness) {
    n = sp.normal;
    target = sp.closest + thickness * n;
    kind = 1;
  } else {
    return 0;
  }
  const double correction = (target - p1).dot(n);
  if (mu > 0.0 && correction > 0.0) {
    const Eigen::Vector3d d = target - p0;
    const Eigen::Vector3d u = d - d.dot(n) * n;
    const double slip = u.norm();
    if (slip <= mu * correction) {
      target -= u;
      kind |= 4;
    } else {
      target -= (mu * correction / slip) * u;
    }
  }
  return kind;
}

AvatarContactStats AvatarContacts::addConstraints(const Eigen::MatrixX3d& xFree, ContactAccumulator& acc) {
  // Watched DOFs: the candidates, then the DOFs that moved at least their distance bound minus the reach.
  std::vector<int> watched = m_candidates;
  if (!m_bound.empty()) {
    const double reach = m_options.thickness + m_options.margin;
    std::vector<char> isCandidate(m_bound.size(), 0);
    for (int d : m_candidates) isCandidate[d] = 1;
    for (int d = 0; d < static_cast<int>(m_bound.size()); ++d) {
      if (isCandidate[d]) continue;
      const double allowed = m_bound[d] - reach;
      if (allowed <= 0.0 || (xFree.row(d) - m_freeStart.row(d)).squaredNorm() >= allowed * allowed)
        watched.push_back(d);
    }
  }
  const int nw = static_cast<int>(watched.size());
  std::vector<char> kind(nw, 0);
  std::vector<Eigen::Vector3d> target(nw);
  tbb::parallel_for(0, nw, [&](int i) {
    const int d = watched[i];
    kind[i] = constrain(m_freeStart.row(d).transpose(), xFree.row(d).transpose(), target[i]);
    if (!m_options.holdTargets || !kind[i]) return;
    if (m_heldKind[d]) {
      target[i] = m_held[d];
      kind[i] = m_heldKind[d];
    } else {
      m_held[d] = target[i];
      m_heldKind[d] = kind[i];
    }
  });
  AvatarContactStats stats;
  for (int i = 0; i < nw; ++i) {
    if (!kind[i]) continue;
    acc.add(watched[i], target[i], m_options.weight);
    ++stats.contacts;
    stats.ccdContacts += (kind[i] & 3) == 2;
    stats.staticFriction += (kind[i] & 4) != 0;
  }
  return stats;
}

}  // namespace drape::pd
