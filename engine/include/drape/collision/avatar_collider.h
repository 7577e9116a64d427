#pragma once
// Static avatar collider: a closed, outward-oriented triangle mesh with an LBVH, answering closest-point and
// signed-distance queries. The sign comes from the angle-weighted pseudo-normal of the closest feature (face,
// edge or vertex; Baerentzen and Aanaes 2005), which is exact for a closed, consistently oriented mesh.
#include <Eigen/Core>
#include <array>
#include <limits>
#include <vector>

#include "drape/collision/bvh.h"
#include "drape/collision/distance.h"
#include "drape/geometry/triangle_mesh.h"

namespace drape::collision {

struct SurfacePoint {
  double signedDistance = 0.0;                        // metres, negative inside the avatar
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();  // closest point on the surface
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();   // unit outward direction: gradient of the signed distance
  int triangle = -1;
  TriangleRegion region = TriangleRegion::Face;
};

// Triangles near the place a moving point (a garment vertex) was last searched from, kept by the point's owner
// between queries: every triangle not listed is at least `complete` from `center`.
struct NearbyTriangles {
  static constexpr int kCapacity = 16;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double complete = 0.0;  // 0: nothing known
  int count = 0;
  std::array<int, kCapacity> triangles{};
};

class AvatarCollider {
 public:
  // mesh: closed, counter-clockwise seen from outside (drape::isClosedManifold); metres. Builds the BVH and the
  // face, edge and vertex pseudo-normals. An open mesh still works but its sign is unreliable near the holes.
  explicit AvatarCollider(TriangleMesh mesh);

  // Closest surface point to p among those with unsigned distance < maxDistance (metres); false when none.
  // hint: a triangle likely to be (nearly) the closest, e.g. the answer for the same vertex a moment earlier, or
  // -1. Its distance starts the search's bound, so the tree walk skips everything farther: the answer is the
  // same, only found faster. When the hint's distance plus the bound (the smaller of maxDistance and the hint's
  // distance) is at most hintRadius(), every triangle that could be closer lies within hintRadius() of the hint
  // (triangle inequality), and only those, listed at construction, are searched instead of the tree.
  bool closest(const Eigen::Vector3d& p, SurfacePoint& out,
               double maxDistance = std::numeric_limits<double>::infinity(), int hint = -1) const;
  // The answer of closest(p, out, maxDistance) (the same point and distance; the triangle may differ only where two
  // share the closest point), taken from `nearby` alone when the list settles it: the best listed triangle is no
  // farther than the list's reach at p, complete - |p - center| (nothing unlisted can be closer), or none is
  // within maxDistance and maxDistance is within that reach. Otherwise a hinted query (the best listed triangle),
  // after which `nearby` lists the triangles within the answer's distance plus 2 reuseRadius() of p: the next
  // queries of a point that moved less than reuseRadius() are settled by the list (unless more than kCapacity
  // triangles lie that close: the nearest are kept, with a shorter reach). Points farther from the surface
  // than 8 reuseRadius() (or with nothing within maxDistance) get an empty list: their neighbourhood is large, and
  // the callers' distance bounds skip most of their queries anyway.
  bool closest(const Eigen::Vector3d& p, SurfacePoint& out, double maxDistance, NearbyTriangles& nearby) const;
  // A quarter of the mesh's mean edge length, metres.
  double reuseRadius() const { return m_nearRadius / 6.0; }
  // Radius of the hint's neighbourhood (1.5 mean edge lengths of the mesh), metres.
  double hintRadius() const { return m_nearRadius; }
  // Signed distance of p (metres): negative inside. Unbounded query.
  double signedDistance(const Eigen::Vector3d& p) const;

  const TriangleMesh& mesh() const { return m_mesh; }
  const Bvh& tree() const { return m_tree; }

 private:
  Eigen::Vector3d pseudoNormal(int triangle, TriangleRegion region) const;
  // The surface point of p on triangle f, whose closest point to p is r.
  void fill(const Eigen::Vector3d& p, int f, const PointTriangleResult& r, SurfacePoint& out) const;
  PointTriangleResult closestOn(const Eigen::Vector3d& p, int f) const;
  // Lists in `nearby` the triangles within radius of p (the nearest kCapacity of them when there are more).
  void listNearby(const Eigen::Vector3d& p, double radius, NearbyTriangles& nearby) const;
  // Lists, per triangle, the triangles whose bounding boxes come within m_nearRadius of its box (a superset of those
  // within m_nearRadius of it).
  void buildNeighbourhoods(const std::vector<BoundingBox>& boxes);
  // Closest triangle to p among [first, last) (culled by their bounding spheres) with squared distance below best2;
  // best2 and result are updated to it; -1 when none.
  int nearestAmong(const Eigen::Vector3d& p, const int* first, const int* last, double& best2,
                   PointTriangleResult& result) const;

  TriangleMesh m_mesh;
  Bvh m_tree;
  std::vector<Eigen::Vector3d> m_faceNormals;    // |F|, unit
  std::vector<Eigen::Vector3d> m_vertexNormals;  // |V|, angle-weighted, unit
  std::vector<Eigen::Vector3d> m_edgeNormals;    // 3|F|: edge k of face f (AB, BC, CA) at 3f + k, unit
  double m_nearRadius = 0.0;
  std::vector<int> m_nearStart;            // |F| + 1: the neighbours of f are m_near[m_nearStart[f] ..)
  std::vector<int> m_near;
  std::vector<Eigen::Vector4d> m_spheres;  // |F|: centroid and the distance of its farthest corner
};

}  // namespace drape::collision
