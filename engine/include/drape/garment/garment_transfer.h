#pragma once
// Carries positions from one meshing of a pattern to another: every vertex of the target garment takes the point
// of the source garment's panel at its own pattern coordinates (the nearest point of that panel's triangles,
// where the two meshings' curved outlines differ), as barycentric weights of the source triangle's vertices.
#include <Eigen/Sparse>

#include "drape/garment/garment.h"

namespace drape {

// |V_to| x |V_from|, at most three non-negative weights per row summing to one: to.positions ~ T * from.positions
// for the same deformation. Both garments must mesh the same pattern (panel names in the same order); throws
// std::invalid_argument when they do not or when a panel of `to` has no triangle in `from`.
Eigen::SparseMatrix<double, Eigen::RowMajor> garmentTransfer(const Garment& from, const Garment& to);

}  // namespace drape
