#pragma once
// Self-intersections of a triangle mesh: pairs of triangles that cross each other although they share no vertex
// (a cloth passing through itself). Broad phase: the LBVH (bvh.h) over the triangles' boxes; narrow phase: an exact
// triangle-triangle test (CGAL's filtered predicates), so touching and coplanar overlaps count as well.
#include <Eigen/Core>
#include <utility>
#include <vector>

namespace drape::collision {

// Whether the closed triangles (a0, a1, a2) and (b0, b1, b2) share a point (exact predicates). A triangle collapsed
// to a segment is tested as that segment, one collapsed to a point as that point.
bool trianglesIntersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                        const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2);

struct SelfIntersections {
  int count = 0;           // intersecting pairs of triangles that share no vertex
  int firstTriangle = -1;  // the pair with the smallest first triangle index (then second), -1 when none
  int secondTriangle = -1;
};

// Counts the pairs of triangles (rows of `triangles`, indices into the rows of `positions`, metres) that intersect
// and share no vertex. Vertices joined by a pair in `joined` count as one vertex (transitively), so that triangles
// meeting at a sewn seam, whose two sides have a vertex each, are neighbours and not an intersection.
SelfIntersections countSelfIntersections(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& triangles,
                                         const std::vector<std::pair<int, int>>& joined = {});

// The same pairs listed: (t, u) with t < u, sorted. positions: flat, size 3|V| (x, y, z of each vertex).
std::vector<std::pair<int, int>> selfIntersectingPairs(const Eigen::VectorXd& positions,
                                                       const Eigen::MatrixX3i& triangles,
                                                       const std::vector<std::pair<int, int>>& joined = {});

}  // namespace drape::collision
