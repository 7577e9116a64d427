#include "drape/pd/avatar_collision.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

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
  constexpr double kUnbounded = std::numeric_limits<double>::infinity();
  std::vector<char> near(nf, 0);
  m_bound.assign(nf, 0.0f);
  m_freeStart.resize(nf, 3);
  m_freePredicted.resize(nf, 3);
  if (static_cast<int>(m_nearby.size()) != nf) m_nearby.assign(nf, collision::NearbyTriangles{});
  m_startInside.assign(nf, 0);
  m_startClosest.resize(nf);
  m_startNormal.resize(nf);
  if (m_queriedAt.rows() != nf) {  // first step (or another set of DOFs): nothing to carry over
    m_queriedAt.resize(nf, 3);
    m_queriedBound.assign(nf, -1.0);
  }
  if (m_options.targets == ContactTargetKind::StepPlanes) m_planes.assign(nf, StepPlanes{});
  tbb::parallel_for(0, nf, [&](int d) {
    const int v = freeVertices[d];
    m_freeStart.row(d) = start.row(v);
    m_freePredicted.row(d) = predicted.row(v);
    const double travel = (predicted.row(v) - start.row(v)).norm();
    const double watch = reach + 2.0 * travel;
    // Rounded down so that the bound stays a lower bound in single precision.
    const auto keep = [&](double bound) { m_bound[d] = static_cast<float>(bound * (1.0 - 1e-6)); };
    // Carried over: the distance to the (fixed) collider changes no faster than the position, so the bound of the
    // last query, less the distance moved since, is still a bound; while it exceeds the watch, no query is needed.
    if (m_queriedBound[d] >= 0.0) {
      const double carried = m_queriedBound[d] - (start.row(v) - m_queriedAt.row(d)).norm();
      if (carried > watch) {
        keep(carried);
        return;
      }
    }
    collision::SurfacePoint sp;
    // Nothing within the radius: far outside, or deep inside (a garment placed through the body); the unbounded
    // query tells which (and, outside, gives a bound that lasts longer).
    const bool found = m_collider->closest(start.row(v).transpose(), sp, watch + kBoundSlack, m_nearby[d]) ||
                       m_collider->closest(start.row(v).transpose(), sp, kUnbounded, m_nearby[d]);
    m_startInside[d] = found && sp.signedDistance < 0.0;
    if (m_startInside[d]) {
      m_startClosest[d] = sp.closest;
      m_startNormal[d] = sp.normal;
    }
    near[d] = found && sp.signedDistance < watch;
    m_queriedAt.row(d) = start.row(v);
    m_queriedBound[d] = found ? std::max(sp.signedDistance, 0.0) : watch + kBoundSlack;
    keep(m_queriedBound[d]);
  });
  // Sized whether or not targets are held now: the preview may switch holding on between steps (setHoldTargets).
  m_held.resize(nf);
  m_heldNormal.resize(nf);
  m_heldKind.assign(nf, 0);
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

char AvatarContacts::constrain(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& z,
                               bool startInside, const Eigen::Vector3d& startClosest,
                               const Eigen::Vector3d& startNormal, Eigen::Vector3d& target, Eigen::Vector3d& normal,
                               collision::NearbyTriangles& nearby) const {
  const double thickness = m_options.thickness;
  const double reach = thickness + m_options.margin;
  collision::SurfacePoint sp;
  const bool near = m_collider->closest(p1, sp, reach, nearby);
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
  } else if (!near && startInside) {
    // Started inside and now deeper than the reach: back out through the start's closest surface, the side it
    // is nearest to (for a vertex that went in during the last step, the side it came from).
    n = startNormal;
    target = p1 + std::max(thickness - (p1 - startClosest).dot(n), 0.0) * n;
    kind = 1;
  } else {
    return 0;
  }
  normal = n;
  const double correction = (target - p1).dot(n);
  const double load = m_options.frictionLoad == FrictionLoadKind::Inertial ? (target - z).dot(n) : correction;
  if (correction > 0.0 && applyFriction(p0, n, load, target)) kind |= 4;
  return kind;
}

bool AvatarContacts::applyFriction(const Eigen::Vector3d& start, const Eigen::Vector3d& n, double c,
                                   Eigen::Vector3d& target) const {
  const double mu = m_options.friction;
  if (!(mu > 0.0) || !(c > 0.0)) return false;
  const Eigen::Vector3d d = target - start;
  const Eigen::Vector3d u = d - d.dot(n) * n;
  const double slip = u.norm();
  if (slip <= mu * c) {
    target -= u;
    return true;
  }
  target -= (mu * c / slip) * u;
  return false;
}

Eigen::Vector3d AvatarContacts::projectToPlanes(const StepPlanes& planes, Eigen::Vector3d x) const {
  const double thickness = m_options.thickness;
  // One plane: exact in one pass. Several: cyclic projections (a few passes reach the intersection of the
  // shallow wedges of a body crease to well under the thickness).
  const int passes = planes.count > 1 ? 6 : 1;
  for (int pass = 0; pass < passes; ++pass)
    for (int i = 0; i < planes.count; ++i) {
      const double gap = (x - planes.point[i]).dot(planes.normal[i]);
      if (gap < thickness) x += (thickness - gap) * planes.normal[i];
    }
  return x;
}

char AvatarContacts::constrainToPlanes(int d, const Eigen::Vector3d& x, Eigen::Vector3d& target, int& added) {
  const double thickness = m_options.thickness;
  const double reach = thickness + m_options.margin;
  const Eigen::Vector3d s = m_freeStart.row(d).transpose();
  StepPlanes& planes = m_planes[d];
  added = 0;
  const auto addPlane = [&](const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
    if (planes.count >= kMaxPlanes || !(normal.squaredNorm() > 0.5)) return false;
    planes.point[planes.count] = point;
    planes.normal[planes.count] = normal;
    ++planes.count;
    ++added;
    return true;
  };
  // The half-space of the start position: looked for (within reach of the segment start -> x) until found.
  if (m_options.ccd && planes.count == 0 && !planes.started) {
    const double radius =
        m_startInside[d] ? std::numeric_limits<double>::infinity() : reach + (x - s).norm();
    collision::SurfacePoint sp;
    if (m_collider->closest(s, sp, radius)) {
      addPlane(sp.closest, sp.normal);
      planes.started = true;
    }
  }
  target = projectToPlanes(planes, x);
  // Check against the real surface; add the half-space of what the target violates.
  for (int round = planes.count; round < kMaxPlanes; ++round) {
    collision::SurfacePoint sp;
    const bool found = m_collider->closest(target, sp, reach);
    const double limit = planes.count == 0 ? thickness : 0.5 * thickness;
    const double travel = (target - s).norm();
    int f = -1;
    if (m_options.ccd && travel > 0.0 && (found ? sp.signedDistance < 0.0 : travel >= reach))
      f = firstCrossing(s, target);
    bool grew = false;
    if (f >= 0) {
      const TriangleMesh& mesh = m_collider->mesh();
      const collision::PointTriangleResult cp = collision::closestPointTriangle(
          target, mesh.vertices.row(mesh.triangles(f, 0)).transpose(),
          mesh.vertices.row(mesh.triangles(f, 1)).transpose(), mesh.vertices.row(mesh.triangles(f, 2)).transpose());
      grew = addPlane(cp.closest, m_faceNormals[f]);
    } else if (found && sp.signedDistance < limit) {
      grew = addPlane(sp.closest, sp.normal);
    }
    if (!grew) break;
    target = projectToPlanes(planes, x);
  }
  const Eigen::Vector3d correction = target - x;
  const double depth = correction.norm();
  if (!(depth > 0.0)) return 0;
  const Eigen::Vector3d n = correction / depth;
  char kind = 1;
  for (int i = 0; i < planes.count; ++i)
    if ((x - planes.point[i]).dot(planes.normal[i]) < 0.0) kind = 2;
  double load = depth;
  if (m_options.frictionLoad == FrictionLoadKind::Inertial) {
    const Eigen::Vector3d z = m_freePredicted.row(d).transpose();
    load = 0.0;
    for (int i = 0; i < planes.count; ++i)
      load = std::max(load, thickness - (z - planes.point[i]).dot(planes.normal[i]));
  }
  if (applyFriction(s, n, load, target)) kind |= 4;
  return kind;
}

int AvatarContacts::resolve(Eigen::MatrixX3d& x, const std::vector<int>& freeVertices,
                            const std::vector<char>* skip) const {
  const int nf = static_cast<int>(freeVertices.size());
  if (static_cast<int>(m_bound.size()) != nf) return 0;
  const double thickness = m_options.thickness;
  const double reach = thickness + m_options.margin;
  std::vector<char> moved(nf, 0);
  tbb::parallel_for(0, nf, [&](int d) {
    if (skip && (*skip)[d]) return;
    const Eigen::Vector3d p1 = x.row(freeVertices[d]).transpose();
    // Outside at the start by at least the bound, and moved less than the bound plus the thickness: not that deep.
    if (!m_startInside[d] && (p1 - m_freeStart.row(d).transpose()).norm() < m_bound[d] + thickness) return;
    collision::SurfacePoint sp;
    if (!m_collider->closest(p1, sp, reach) || sp.signedDistance >= -thickness) return;
    x.row(freeVertices[d]) = (sp.closest + thickness * sp.normal).transpose();
    moved[d] = 1;
  });
  int count = 0;
  for (char m : moved) count += m;
  return count;
}

AvatarContactStats AvatarContacts::addConstraints(const Eigen::MatrixX3d& xFree, ContactAccumulator& acc) {
  // Watched DOFs (header). The bound is a distance at the step start: a DOF that moved by s is at least
  // bound - s from the surface, and a segment shorter than its start's distance cannot cross it.
  // StepPlanes: every candidate, and the others once they moved within thickness + margin (their half-spaces
  // carry state between iterations). Reproject: within the thickness, widened by a part in a million because the
  // bound is rounded down.
  const bool planes = m_options.targets == ContactTargetKind::StepPlanes;
  const double slack = planes ? m_options.thickness + m_options.margin : m_options.thickness * (1.0 + 1e-6);
  std::vector<int> watched = planes ? m_candidates : std::vector<int>{};
  std::vector<char> listed(m_bound.size(), 0);
  for (int d : watched) listed[d] = 1;
  for (int d = 0; d < static_cast<int>(m_bound.size()); ++d) {
    if (listed[d]) continue;
    const double allowed = m_bound[d] - slack;
    if (allowed <= 0.0 || (xFree.row(d) - m_freeStart.row(d)).squaredNorm() >= allowed * allowed)
      watched.push_back(d);
  }
  const int nw = static_cast<int>(watched.size());
  std::vector<char> kind(nw, 0);
  std::vector<int> added(nw, 0);
  std::vector<Eigen::Vector3d> target(nw);
  tbb::parallel_for(0, nw, [&](int i) {
    const int d = watched[i];
    const Eigen::Vector3d x = xFree.row(d).transpose();
    if (m_options.holdTargets && !planes && m_heldKind[d]) {  // held (header): no lookup
      if ((x - m_held[d]).dot(m_heldNormal[d]) < 0.0) {
        target[i] = m_held[d];
        kind[i] = m_heldKind[d];
      }
      return;
    }
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    kind[i] = planes ? constrainToPlanes(d, x, target[i], added[i])
                     : constrain(m_freeStart.row(d).transpose(), x, m_freePredicted.row(d).transpose(),
                                 m_startInside[d] != 0, m_startClosest[d], m_startNormal[d], target[i], normal,
                                 m_nearby[d]);
    if (!m_options.holdTargets || !kind[i]) return;
    if (m_heldKind[d]) {  // StepPlanes
      target[i] = m_held[d];
      kind[i] = m_heldKind[d];
    } else {
      m_held[d] = target[i];
      m_heldNormal[d] = normal;
      m_heldKind[d] = kind[i];
    }
  });
  AvatarContactStats stats;
  stats.watched = nw;
  for (int i = 0; i < nw; ++i) {
    stats.planesAdded += added[i];
    if (!kind[i]) continue;
    acc.add(watched[i], target[i], m_options.weight);
    ++stats.contacts;
    stats.ccdContacts += (kind[i] & 3) == 2;
    stats.staticFriction += (kind[i] & 4) != 0;
  }
  return stats;
}

}  // namespace drape::pd
