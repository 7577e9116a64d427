// Pseudo-normals: face normal for the face region, the sum of the two incident face normals for an edge, the
// incident face normals weighted by their corner angles for a vertex. Edges are matched through a sorted list.
#include "drape/collision/avatar_collider.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <tuple>

#include <tbb/parallel_for.h>

namespace drape::collision {
namespace {

Eigen::Vector3d safeNormalized(const Eigen::Vector3d& v) {
  const double n = v.norm();
  return n > 0.0 ? Eigen::Vector3d(v / n) : Eigen::Vector3d::Zero();
}

}  // namespace

AvatarCollider::AvatarCollider(TriangleMesh mesh) : m_mesh(std::move(mesh)) {
  const int faces = m_mesh.triangleCount();
  const auto& V = m_mesh.vertices;
  const auto& F = m_mesh.triangles;
  m_faceNormals.resize(faces);
  m_vertexNormals.assign(m_mesh.vertexCount(), Eigen::Vector3d::Zero());
  m_edgeNormals.assign(3 * faces, Eigen::Vector3d::Zero());
  std::vector<BoundingBox> boxes(faces);
  for (int f = 0; f < faces; ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0));
    const Eigen::Vector3d b = V.row(F(f, 1));
    const Eigen::Vector3d c = V.row(F(f, 2));
    m_faceNormals[f] = safeNormalized((b - a).cross(c - a));
    boxes[f] = boxOf(a, b, c);
    const Eigen::Vector3d corners[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = safeNormalized(corners[(k + 1) % 3] - corners[k]);
      const Eigen::Vector3d w = safeNormalized(corners[(k + 2) % 3] - corners[k]);
      const double angle = std::acos(std::clamp(u.dot(w), -1.0, 1.0));
      m_vertexNormals[F(f, k)] += angle * m_faceNormals[f];
    }
  }
  for (auto& n : m_vertexNormals) n = safeNormalized(n);

  // Edge (min, max, face, local edge), sorted so that the two faces of an edge are adjacent in the list.
  std::vector<std::tuple<int, int, int, int>> halfEdges;
  halfEdges.reserve(3 * faces);
  for (int f = 0; f < faces; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k);
      const int b = F(f, (k + 1) % 3);
      halfEdges.emplace_back(std::min(a, b), std::max(a, b), f, k);
    }
  }
  std::sort(halfEdges.begin(), halfEdges.end());
  for (std::size_t i = 0; i < halfEdges.size();) {
    std::size_t j = i;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    while (j < halfEdges.size() && std::get<0>(halfEdges[j]) == std::get<0>(halfEdges[i]) &&
           std::get<1>(halfEdges[j]) == std::get<1>(halfEdges[i])) {
      sum += m_faceNormals[std::get<2>(halfEdges[j])];
      ++j;
    }
    const Eigen::Vector3d n = safeNormalized(sum);
    for (std::size_t k = i; k < j; ++k) m_edgeNormals[3 * std::get<2>(halfEdges[k]) + std::get<3>(halfEdges[k])] = n;
    i = j;
  }
  m_tree.build(boxes);
  buildNeighbourhoods(boxes);
}

void AvatarCollider::buildNeighbourhoods(const std::vector<BoundingBox>& boxes) {
  const int faces = m_mesh.triangleCount();
  const auto& V = m_mesh.vertices;
  const auto& F = m_mesh.triangles;
  double edgeSum = 0.0;
  m_spheres.resize(faces);
  for (int f = 0; f < faces; ++f) {
    const Eigen::Vector3d corners[3] = {V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2))};
    const Eigen::Vector3d centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
    double radius = 0.0;
    for (int k = 0; k < 3; ++k) {
      radius = std::max(radius, (corners[k] - centroid).norm());
      edgeSum += (corners[(k + 1) % 3] - corners[k]).norm();
    }
    m_spheres[f] << centroid, radius;
  }
  m_nearRadius = faces > 0 ? 1.5 * edgeSum / (3.0 * faces) : 0.0;
  const double r2 = m_nearRadius * m_nearRadius;
  std::vector<std::vector<int>> lists(faces);
  tbb::parallel_for(0, faces, [&](int f) {
    m_tree.forEachOverlap(inflated(boxes[f], m_nearRadius), [&](int g) {
      if (squaredDistance(boxes[f], boxes[g]) <= r2) lists[f].push_back(g);
    });
  });
  m_nearStart.assign(faces + 1, 0);
  for (int f = 0; f < faces; ++f) m_nearStart[f + 1] = m_nearStart[f] + static_cast<int>(lists[f].size());
  m_near.resize(m_nearStart[faces]);
  for (int f = 0; f < faces; ++f) std::copy(lists[f].begin(), lists[f].end(), m_near.begin() + m_nearStart[f]);
}

int AvatarCollider::nearestAmong(const Eigen::Vector3d& p, const int* first, const int* last, double& best2,
                                 PointTriangleResult& result) const {
  int best = -1;
  double bound = std::sqrt(best2);
  for (const int* it = first; it != last; ++it) {
    const int g = *it;
    // Every point of g is at least |p - centroid| - radius from p.
    const Eigen::Vector4d& sphere = m_spheres[g];
    const double reach = sphere[3] + bound;
    if ((p - sphere.head<3>()).squaredNorm() >= reach * reach) continue;
    const PointTriangleResult r = closestOn(p, g);
    if (r.distanceSquared < best2) {
      best2 = r.distanceSquared;
      bound = std::sqrt(best2);
      best = g;
      result = r;
    }
  }
  return best;
}

Eigen::Vector3d AvatarCollider::pseudoNormal(int triangle, TriangleRegion region) const {
  switch (region) {
    case TriangleRegion::Face: return m_faceNormals[triangle];
    case TriangleRegion::EdgeAB: return m_edgeNormals[3 * triangle];
    case TriangleRegion::EdgeBC: return m_edgeNormals[3 * triangle + 1];
    case TriangleRegion::EdgeCA: return m_edgeNormals[3 * triangle + 2];
    case TriangleRegion::VertexA: return m_vertexNormals[m_mesh.triangles(triangle, 0)];
    case TriangleRegion::VertexB: return m_vertexNormals[m_mesh.triangles(triangle, 1)];
    case TriangleRegion::VertexC: return m_vertexNormals[m_mesh.triangles(triangle, 2)];
  }
  return m_faceNormals[triangle];
}

bool AvatarCollider::closest(const Eigen::Vector3d& p, SurfacePoint& out, double maxDistance, int hint) const {
  const auto& V = m_mesh.vertices;
  const auto& F = m_mesh.triangles;
  auto corner = [&](int f, int k) -> Eigen::Vector3d { return V.row(F(f, k)).transpose(); };
  double best2 = std::isfinite(maxDistance) ? maxDistance * maxDistance : std::numeric_limits<double>::infinity();
  int seed = -1;
  bool local = false;
  if (hint >= 0 && hint < m_mesh.triangleCount()) {
    const double d2 = closestPointTriangle(p, corner(hint, 0), corner(hint, 1), corner(hint, 2)).distanceSquared;
    if (d2 < best2) {
      best2 = d2;
      seed = hint;
    }
    // A triangle closer than sqrt(best2) has a point within sqrt(d2) + sqrt(best2) of the hint's closest point.
    local = std::sqrt(d2) + std::sqrt(best2) <= m_nearRadius;
  }
  PointTriangleResult listed;  // the closest point on f when the neighbourhood search found it
  int f = local ? nearestAmong(p, m_near.data() + m_nearStart[hint], m_near.data() + m_nearStart[hint + 1], best2,
                               listed)
                : m_tree.nearest(
                      p,
                      [&](int t) {
                        return closestPointTriangle(p, corner(t, 0), corner(t, 1), corner(t, 2)).distanceSquared;
                      },
                      best2);
  if (local && f >= 0) {
    fill(p, f, listed, out);
    return true;
  }
  if (f < 0) f = seed;  // nothing strictly closer than the hint
  if (f < 0) return false;
  fill(p, f, closestOn(p, f), out);
  return true;
}

PointTriangleResult AvatarCollider::closestOn(const Eigen::Vector3d& p, int f) const {
  const auto& V = m_mesh.vertices;
  const auto& F = m_mesh.triangles;
  return closestPointTriangle(p, V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(), V.row(F(f, 2)).transpose());
}

void AvatarCollider::fill(const Eigen::Vector3d& p, int f, const PointTriangleResult& r, SurfacePoint& out) const {
  const Eigen::Vector3d pn = pseudoNormal(f, r.region);
  const Eigen::Vector3d offset = p - r.closest;
  const double distance = std::sqrt(r.distanceSquared);
  const double sign = offset.dot(pn) < 0.0 ? -1.0 : 1.0;
  out.signedDistance = sign * distance;
  out.closest = r.closest;
  // The gradient of the signed distance is the unit offset times the sign; on the surface use the pseudo-normal.
  out.normal = distance > 1e-12 ? Eigen::Vector3d(sign * offset / distance) : pn;
  out.triangle = f;
  out.region = r.region;
}

bool AvatarCollider::closest(const Eigen::Vector3d& p, SurfacePoint& out, double maxDistance,
                             NearbyTriangles& nearby) const {
  const double reach = nearby.complete - (p - nearby.center).norm();
  double best2 = std::numeric_limits<double>::infinity();
  PointTriangleResult bestResult;
  // Nearest first (listNearby): the spheres skip most of the rest.
  const int best = nearestAmong(p, nearby.triangles.data(), nearby.triangles.data() + nearby.count, best2, bestResult);
  if (reach > 0.0) {
    if (best >= 0 && best2 <= reach * reach) {  // nothing unlisted is closer
      if (!(best2 < maxDistance * maxDistance)) return false;
      fill(p, best, bestResult, out);
      return true;
    }
    if (maxDistance <= reach) return false;  // listed and unlisted triangles alike are at least maxDistance away
  }
  const bool found = closest(p, out, maxDistance, best);
  const double slack = 2.0 * reuseRadius();
  if (found && std::abs(out.signedDistance) <= 4.0 * slack)
    listNearby(p, std::abs(out.signedDistance) + slack, nearby);
  else
    nearby = NearbyTriangles{};
  return found;
}

void AvatarCollider::listNearby(const Eigen::Vector3d& p, double radius, NearbyTriangles& nearby) const {
  std::array<std::pair<double, int>, 4 * NearbyTriangles::kCapacity> found;
  int count = 0;
  double complete = radius;
  const double r2 = radius * radius;
  m_tree.forEachOverlap(inflated(boxOf(p, p), radius), [&](int f) {
    const Eigen::Vector4d& sphere = m_spheres[f];
    const double reach = sphere[3] + radius;
    if ((p - sphere.head<3>()).squaredNorm() >= reach * reach) return;
    const double d2 = closestOn(p, f).distanceSquared;
    if (d2 >= r2 || d2 >= complete * complete) return;
    if (count == static_cast<int>(found.size())) {  // full: keep the nearest kCapacity; the next bounds the rest
      std::nth_element(found.begin(), found.begin() + NearbyTriangles::kCapacity, found.end());
      complete = std::sqrt(found[NearbyTriangles::kCapacity].first);
      count = NearbyTriangles::kCapacity;
      if (d2 >= complete * complete) return;
    }
    found[count++] = {d2, f};
  });
  if (count > NearbyTriangles::kCapacity) {
    std::nth_element(found.begin(), found.begin() + NearbyTriangles::kCapacity, found.begin() + count);
    complete = std::min(complete, std::sqrt(found[NearbyTriangles::kCapacity].first));
    count = NearbyTriangles::kCapacity;
  }
  std::sort(found.begin(), found.begin() + count);
  nearby.center = p;
  nearby.complete = complete;
  nearby.count = count;
  for (int k = 0; k < count; ++k) nearby.triangles[k] = found[k].second;
}

double AvatarCollider::signedDistance(const Eigen::Vector3d& p) const {
  SurfacePoint s;
  return closest(p, s) ? s.signedDistance : std::numeric_limits<double>::infinity();
}

}  // namespace drape::collision
