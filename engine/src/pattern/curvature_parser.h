#pragma once
// Private: reads an edge's "curvature" field into an EdgeCurve with relative control points.
// Accepts the legacy bare [x, y] (quadratic Bezier control point) and the v2 objects
// {"type": "quadratic"|"cubic"|"circle", "params": ...}; see docs/FORMATS.md "Pattern files".
#include <Eigen/Core>
#include <string>

#include "drape/pattern/pattern.h"
#include "pattern/json_fields.h"

namespace drape::detail {

// value: the "curvature" JSON value. where: "panel 'x' edge i" for messages. absolute: curvature_coords is
// "absolute" (control points in panel coordinates, converted here to relative). start, end: the edge's
// endpoint positions (distinct).
EdgeCurve parseCurvature(const Json& value, const JsonFields& fields, const std::string& where, bool absolute,
                         const Eigen::Vector2d& start, const Eigen::Vector2d& end);

}  // namespace drape::detail
