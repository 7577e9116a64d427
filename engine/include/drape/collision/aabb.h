#pragma once
// Axis-aligned box helpers on drape::BoundingBox for the broad phase. Lengths in metres.
#include <Eigen/Core>
#include <algorithm>

#include "drape/geometry/triangle_mesh.h"

namespace drape::collision {

// True when the closed boxes share at least one point (touching counts). Empty boxes overlap nothing.
inline bool overlaps(const BoundingBox& a, const BoundingBox& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

// Box grown by r >= 0 on every side.
inline BoundingBox inflated(const BoundingBox& b, double r) {
  BoundingBox out;
  out.min = b.min.array() - r;
  out.max = b.max.array() + r;
  return out;
}

// Squared distance from p to the box (0 inside), m^2.
inline double squaredDistance(const BoundingBox& b, const Eigen::Vector3d& p) {
  const Eigen::Vector3d excess = (b.min - p).cwiseMax(p - b.max).cwiseMax(0.0);
  return excess.squaredNorm();
}

// Squared distance between two boxes (0 when they overlap), m^2.
inline double squaredDistance(const BoundingBox& a, const BoundingBox& b) {
  const Eigen::Vector3d gap = (a.min - b.max).cwiseMax(b.min - a.max).cwiseMax(0.0);
  return gap.squaredNorm();
}

inline BoundingBox boxOf(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  BoundingBox out;
  out.min = a.cwiseMin(b);
  out.max = a.cwiseMax(b);
  return out;
}

inline BoundingBox boxOf(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  BoundingBox out;
  out.min = a.cwiseMin(b).cwiseMin(c);
  out.max = a.cwiseMax(b).cwiseMax(c);
  return out;
}

}  // namespace drape::collision
