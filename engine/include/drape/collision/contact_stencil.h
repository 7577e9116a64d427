#pragma once
// Contact stencils: the vertices of one vertex-triangle or edge-edge proximity with the weights that give the
// offset r = sum_i w_i x_i between the two closest points, and the exact derivatives of the squared distance
// |r|^2 with the closest-point parameters eliminated (envelope theorem + implicit differentiation).
#include <Eigen/Core>
#include <array>

#include "drape/collision/distance.h"

namespace drape::collision {

// One pair in contact. r = sum_{i < count} weights[i] * x[vertices[i]] points from the second primitive to the
// first (from the triangle to the vertex, from edge b to edge a); normal = r / |r|.
struct ContactStencil {
  std::array<int, 4> vertices{};
  std::array<double, 4> weights{};
  int count = 0;
  double distance = 0.0;                            // |r|, metres (signed for avatar contact: < 0 inside)
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, pushes the first primitive away from the second
};

using Vector12d = Eigen::Matrix<double, 12, 1>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;

// Squared distance D(x) of a 4-vertex stencil and its derivatives in the stacked positions (x0, x1, x2, x3).
struct SquaredDistanceDerivatives {
  double value = 0.0;
  Vector12d gradient = Vector12d::Zero();
  Matrix12d hessian = Matrix12d::Zero();
  Eigen::Vector4d weights = Eigen::Vector4d::Zero();  // r = sum weights_i x_i at the closest points
};

// Point p = x0 against triangle (x1, x2, x3).
SquaredDistanceDerivatives pointTriangleSquaredDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                        const Eigen::Vector3d& b, const Eigen::Vector3d& c);
// Edge (x0, x1) against edge (x2, x3).
SquaredDistanceDerivatives edgeEdgeSquaredDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                                   const Eigen::Vector3d& q0, const Eigen::Vector3d& q1);

// Penalty 0.5 k (thickness - d)^2 for d = sqrt(D) < thickness, as a function of the stencil positions.
// Returns false (and leaves outputs untouched) when d >= thickness or d == 0 (no direction).
// projectToPsd: clamp negative eigenvalues of the 12x12 Hessian to zero.
bool penaltyFromSquaredDistance(const SquaredDistanceDerivatives& D, double stiffness, double thickness,
                                bool projectToPsd, double& energy, Vector12d& gradient, Matrix12d& hessian);

// Symmetric matrix with its negative eigenvalues set to zero.
template <int N>
Eigen::Matrix<double, N, N> projectPsd(const Eigen::Matrix<double, N, N>& m);

}  // namespace drape::collision
