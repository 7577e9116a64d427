#pragma once
// Cache-friendly orderings of 2D points: neighbours in the plane end up near each other in the order, so a
// mesh numbered this way touches nearby memory when it visits a triangle's vertices (the assembly and the
// sparse products of both solvers are bound by memory traffic, not arithmetic).
#include <Eigen/Core>
#include <vector>

namespace drape {

// Position of each point along a Hilbert curve over the points' bounding box (2^16 cells per side).
std::vector<unsigned long long> hilbertKeys(const Eigen::MatrixX2d& points);

// Indices of the points sorted along a Hilbert curve over their bounding box; ties keep index order.
std::vector<int> hilbertOrder(const Eigen::MatrixX2d& points);

}  // namespace drape
