#pragma once
// A plain indexed triangle mesh: the avatar, a collider, or an exported garment.
#include <Eigen/Core>
#include <limits>

namespace drape {

struct TriangleMesh {
  Eigen::MatrixX3d vertices;   // |V| x 3, metres
  Eigen::MatrixX3i triangles;  // |F| x 3, indices into vertices, counter-clockwise seen from outside

  int vertexCount() const { return static_cast<int>(vertices.rows()); }
  int triangleCount() const { return static_cast<int>(triangles.rows()); }
};

struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return (max.array() < min.array()).any(); }
  void extend(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void extend(const BoundingBox& b) {
    if (b.empty()) return;
    extend(b.min);
    extend(b.max);
  }
  Eigen::Vector3d size() const { return empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(max - min); }
  Eigen::Vector3d center() const { return empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.5 * (min + max)); }
};

// Bounds of the rows of an |V| x 3 matrix.
inline BoundingBox boundsOf(const Eigen::MatrixX3d& points) {
  BoundingBox b;
  for (Eigen::Index i = 0; i < points.rows(); ++i) b.extend(points.row(i).transpose());
  return b;
}

}  // namespace drape
