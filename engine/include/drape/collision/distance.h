#pragma once
// Narrow-phase distance primitives: closest points between a point and a triangle (every Voronoi region) and
// between two segments (parallel and degenerate cases included). All lengths in metres.
#include <Eigen/Core>

namespace drape::collision {

// Feature of a triangle (a, b, c) that holds the closest point.
enum class TriangleRegion { Face, EdgeAB, EdgeBC, EdgeCA, VertexA, VertexB, VertexC };

struct PointTriangleResult {
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();      // closest point on the triangle
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  // weights of a, b, c (sum 1, all >= 0)
  TriangleRegion region = TriangleRegion::Face;
  double distanceSquared = 0.0;                           // |p - closest|^2, m^2
};

// Closest point of triangle (a, b, c) to p. Degenerate (zero-area) triangles fall back to their three edges.
PointTriangleResult closestPointTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c);

struct PointSegmentResult {
  double t = 0.0;  // closest point = a + t (b - a), t in [0, 1]
  double distanceSquared = 0.0;
};

// Closest point of segment [a, b] to p; a zero-length segment gives t = 0.
PointSegmentResult closestPointSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

struct EdgeEdgeResult {
  double s = 0.0;  // point on the first edge: p0 + s (p1 - p0), s in [0, 1]
  double t = 0.0;  // point on the second edge: q0 + t (q1 - q0), t in [0, 1]
  double distanceSquared = 0.0;
  bool parallel = false;  // the edges are (nearly) parallel: the closest pair is not unique
};

// Closest points of segments [p0, p1] and [q0, q1]. Parallel edges return one of the closest pairs.
EdgeEdgeResult closestPointsEdgeEdge(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                                     const Eigen::Vector3d& q1);

}  // namespace drape::collision
