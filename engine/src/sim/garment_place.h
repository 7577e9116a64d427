// Places on a garment in words, for messages that name where something happened: "vertex 12 of panel 'front' at
// (x, y, z) m", "triangle 7 of panel 'back'".
#pragma once

#include <Eigen/Core>
#include <string>

#include "drape/garment/garment.h"

namespace drape {

// " of panel 'name'", or "" when the panel index is out of range.
std::string panelOf(const Garment& garment, int panel);
// " at (x, y, z) m", millimetre precision.
std::string atPoint(const Eigen::Vector3d& p);
// "vertex v of panel 'name' at (x, y, z) m" at positions x (|V| x 3, metres).
std::string vertexPlace(const Garment& garment, const Eigen::MatrixX3d& x, int v);
// "triangle t of panel 'name'".
std::string triangleName(const Garment& garment, int t);
// The centroid of triangle t at positions x.
Eigen::Vector3d triangleCentre(const Garment& garment, const Eigen::MatrixX3d& x, int t);

}  // namespace drape
