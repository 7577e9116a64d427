#pragma once
// Per-triangle stretch of a deformed garment relative to its flat pattern.
#include <Eigen/Core>

namespace drape {

// For each triangle, the largest principal stretch minus one (0.05 = stretched 5%, negative = compressed),
// from the deformation gradient between rest (|V| x 2, metres) and positions (|V| x 3, metres).
// Degenerate rest triangles get 0.
Eigen::VectorXd triangleStretch(const Eigen::MatrixX2d& rest, const Eigen::MatrixX3d& positions,
                                const Eigen::MatrixX3i& triangles);

}  // namespace drape
