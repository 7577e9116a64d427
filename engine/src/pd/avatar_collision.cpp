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
  std::vector<char> near(nf, 0);
  tbb::parallel_for(0, nf, [&](int d) {
    const int v = freeVertices[d];
    const double travel = (predicted.row(v) - start.row(v)).norm();
    collision::SurfacePoint sp;
    near[d] = m_collider->closest(start.row(v).transpose(), sp, reach + 2.0 * travel);
  });
  m_candidates.clear();
  m_start.clear();
  for (int d = 0; d < nf; ++d)
    if (near[d]) {
      m_candidates.push_back(d);
      m_start.push_back(start.row(freeVertices[d]).transpose());
    }
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

AvatarContactStats AvatarContacts::addConstraints(const Eigen::MatrixX3d& xFree, ContactAccumulator& acc) const {
  const int nc = static_cast<int>(m_candidates.size());
  const double thickness = m_options.thickness;
  const double reach = thickness + m_options.margin;
  const double mu = m_options.friction;
  // 0: none, 1: proximity, 2: CCD; +4 when static friction held it.
  std::vector<char> kind(nc, 0);
  std::vector<Eigen::Vector3d> target(nc);
  tbb::parallel_for(0, nc, [&](int i) {
    const Eigen::Vector3d& p0 = m_start[i];
    const Eigen::Vector3d p1 = xFree.row(m_candidates[i]).transpose();
    collision::SurfacePoint sp;
    const bool near = m_collider->closest(p1, sp, reach);
    const double travel = (p1 - p0).norm();
    // A segment shorter than the end's distance to the surface cannot have crossed it.
    const bool mayCross = m_options.ccd && travel > 0.0 && (near ? sp.signedDistance < travel : travel >= reach);
    const int f = mayCross ? firstCrossing(p0, p1) : -1;
    Eigen::Vector3d n;
    if (f >= 0) {
      const TriangleMesh& mesh = m_collider->mesh();
      const collision::PointTriangleResult cp = collision::closestPointTriangle(
          p1, mesh.vertices.row(mesh.triangles(f, 0)).transpose(), mesh.vertices.row(mesh.triangles(f, 1)).transpose(),
          mesh.vertices.row(mesh.triangles(f, 2)).transpose());
      n = m_faceNormals[f];
      target[i] = cp.closest + thickness * n;
      kind[i] = 2;
    } else if (near && sp.signedDistance < thickness) {
      n = sp.normal;
      target[i] = sp.closest + thickness * n;
      kind[i] = 1;
    } else {
      return;
    }
    const double correction = (target[i] - p1).dot(n);
    if (mu > 0.0 && correction > 0.0) {
      const Eigen::Vector3d d = target[i] - p0;
      const Eigen::Vector3d u = d - d.dot(n) * n;
      const double slip = u.norm();
      if (slip <= mu * correction) {
        target[i] -= u;
        kind[i] |= 4;
      } else {
        target[i] -= (mu * correction / slip) * u;
      }
    }
  });
  AvatarContactStats stats;
  for (int i = 0; i < nc; ++i) {
    if (!kind[i]) continue;
    acc.add(m_candidates[i], target[i], m_options.weight);
    ++stats.contacts;
    stats.ccdContacts += (kind[i] & 3) == 2;
    stats.staticFriction += (kind[i] & 4) != 0;
  }
  return stats;
}

}  // namespace drape::pd
