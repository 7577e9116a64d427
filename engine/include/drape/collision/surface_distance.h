#pragma once
// Unsigned point-to-surface distance against a triangle mesh (any triangles: open or closed, oriented or not),
// for comparing a drape with a reference drape meshed at another resolution: each reference vertex
// is measured against the other drape's surface, not against a corresponding vertex. The nearest triangle is
// found by branch and bound over an LBVH of the triangle boxes (collision/bvh.h); the per-triangle distance is
// the exact closest point of collision/distance.h. Lengths in metres.
#include <Eigen/Core>

#include "drape/collision/bvh.h"
#include "drape/geometry/triangle_mesh.h"

namespace drape::collision {

// Built once over a surface, queried many times (thread-safe: queries do not modify it).
class SurfaceDistance {
 public:
  // Copies the surface and builds the tree over its triangles. Throws std::invalid_argument when the surface
  // has no triangles or a triangle indexes outside its vertices (the message names the triangle).
  explicit SurfaceDistance(TriangleMesh surface);

  // Unsigned distance (metres) from p to the nearest point of the surface; not finite when p is not.
  double distance(const Eigen::Vector3d& p) const;
  // Unsigned distance (metres) of each row of points (|P| x 3, metres); |P| entries. Rows are queried in
  // parallel (TBB).
  Eigen::VectorXd distances(const Eigen::MatrixX3d& points) const;

  const TriangleMesh& surface() const { return m_surface; }

 private:
  TriangleMesh m_surface;
  Bvh m_tree;  // one box per triangle; primitive id = triangle index
};

// For each row of points (|P| x 3, metres), the unsigned distance (metres) to the nearest point of the triangle
// surface mesh (any triangles, open or closed); |P| entries. Throws std::invalid_argument as SurfaceDistance
// does (no triangles, or an index out of range), even when points is empty.
Eigen::VectorXd distancesToSurface(const Eigen::MatrixX3d& points, const TriangleMesh& surface);

}  // namespace drape::collision
