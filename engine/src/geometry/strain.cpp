#include "drape/geometry/strain.h"

#include <Eigen/Dense>
#include <cmath>

namespace drape {

Eigen::VectorXd triangleStretch(const Eigen::MatrixX2d& rest, const Eigen::MatrixX3d& positions,
                                const Eigen::MatrixX3i& triangles) {
  Eigen::VectorXd stretch = Eigen::VectorXd::Zero(triangles.rows());
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
    Eigen::Matrix2d dm;
    dm.col(0) = (rest.row(b) - rest.row(a)).transpose();
    dm.col(1) = (rest.row(c) - rest.row(a)).transpose();
    const double det = dm.determinant();
    if (!(std::abs(det) > 1e-14)) continue;
    Eigen::Matrix<double, 3, 2> ds;
    ds.col(0) = (positions.row(b) - positions.row(a)).transpose();
    ds.col(1) = (positions.row(c) - positions.row(a)).transpose();
    const Eigen::Matrix<double, 3, 2> f = ds * dm.inverse();
    // Largest singular value of F = sqrt of the largest eigenvalue of the 2x2 right Cauchy-Green tensor.
    const Eigen::Matrix2d c2 = f.transpose() * f;
    const double tr = c2.trace(), dt = c2.determinant();
    const double lambdaMax = 0.5 * tr + std::sqrt(std::max(0.0, 0.25 * tr * tr - dt));
    stretch[t] = std::sqrt(std::max(0.0, lambdaMax)) - 1.0;
  }
  return stretch;
}

}  // namespace drape
