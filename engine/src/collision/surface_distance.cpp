#include "drape/collision/surface_distance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "drape/collision/aabb.h"
#include "drape/collision/distance.h"

namespace drape::collision {

SurfaceDistance::SurfaceDistance(TriangleMesh surface) : m_surface(std::move(surface)) {
  const int nf = m_surface.triangleCount();
  const int nv = m_surface.vertexCount();
  if (nf == 0) throw std::invalid_argument("surface distance: the surface has no triangles");
  const auto& V = m_surface.vertices;
  const auto& F = m_surface.triangles;
  std::vector<BoundingBox> boxes(nf);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      if (F(f, k) < 0 || F(f, k) >= nv) {
        throw std::invalid_argument("surface distance: triangle " + std::to_string(f) + " corner " + std::to_string(k) +
                                    ": vertex " + std::to_string(F(f, k)) + " out of range (surface has " +
                                    std::to_string(nv) + " vertices)");
      }
    }
    boxes[f] = boxOf(V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(), V.row(F(f, 2)).transpose());
  }
  m_tree.build(boxes);
}

double SurfaceDistance::distance(const Eigen::Vector3d& p) const {
  const auto& V = m_surface.vertices;
  const auto& F = m_surface.triangles;
  const auto triangleDistance2 = [&](int f) {
    return closestPointTriangle(p, V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(), V.row(F(f, 2)).transpose())
        .distanceSquared;
  };
  double best2 = std::numeric_limits<double>::infinity();
  m_tree.nearest(p, triangleDistance2, best2);
  return std::sqrt(best2);
}

Eigen::VectorXd SurfaceDistance::distances(const Eigen::MatrixX3d& points) const {
  Eigen::VectorXd out(points.rows());
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, points.rows()),
                    [&](const tbb::blocked_range<Eigen::Index>& range) {
                      for (Eigen::Index i = range.begin(); i != range.end(); ++i) {
                        out[i] = distance(points.row(i).transpose());
                      }
                    });
  return out;
}

Eigen::VectorXd distancesToSurface(const Eigen::MatrixX3d& points, const TriangleMesh& surface) {
  return SurfaceDistance(surface).distances(points);
}

}  // namespace drape::collision
