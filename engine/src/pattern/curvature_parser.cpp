#include "pattern/curvature_parser.h"

#include "pattern/curve_geometry.h"

namespace drape::detail {
namespace {

Eigen::Vector2d readControl(const Json& value, const JsonFields& fields, const std::string& where,
                            const std::string& what, bool absolute, const Eigen::Vector2d& start,
                            const Eigen::Vector2d& end) {
  const Eigen::Vector2d p = fields.readVec2(value, where, what);
  return absolute ? absoluteToRelative(start, end, p) : p;
}

}  // namespace

EdgeCurve parseCurvature(const Json& value, const JsonFields& fields, const std::string& where, bool absolute,
                         const Eigen::Vector2d& start, const Eigen::Vector2d& end) {
  EdgeCurve curve;
  if (value.is_array()) {  // legacy form: one quadratic control point
    curve.type = CurveType::Quadratic;
    curve.controls.push_back(readControl(value, fields, where, "curvature", absolute, start, end));
    return curve;
  }
  if (!value.is_object())
    fields.fail(where,
                "curvature must be [x, y] or an object with \"type\" and \"params\", got " + describeType(value));

  const std::string type =
      fields.readString(fields.member(value, "type", where + " curvature"), where, "curvature type");
  const Json& params = fields.member(value, "params", where + " curvature");
  fields.expectArray(params, where, type + " curvature params");

  if (type == "quadratic") {
    if (params.size() != 1)
      fields.fail(where, "quadratic curvature params must hold 1 control point [[x, y]], got " +
                             std::to_string(params.size()) + " entries");
    curve.type = CurveType::Quadratic;
    curve.controls.push_back(readControl(params[0], fields, where, "quadratic control point", absolute, start, end));
  } else if (type == "cubic") {
    if (params.size() != 2)
      fields.fail(where, "cubic curvature params must hold 2 control points [[x, y], [x, y]], got " +
                             std::to_string(params.size()) + " entries");
    curve.type = CurveType::Cubic;
    curve.controls.push_back(readControl(params[0], fields, where, "cubic control point 1", absolute, start, end));
    curve.controls.push_back(readControl(params[1], fields, where, "cubic control point 2", absolute, start, end));
  } else if (type == "circle") {
    if (params.size() != 3)
      fields.fail(where, "circle curvature params must be [radius, large_arc, right], got " +
                             std::to_string(params.size()) + " entries");
    curve.type = CurveType::Circle;
    curve.radius = fields.readNumber(params[0], where, "circle radius");
    curve.largeArc = fields.readFlag(params[1], where, "circle large_arc flag");
    curve.right = fields.readFlag(params[2], where, "circle right flag");
    const double halfChord = 0.5 * (end - start).norm();
    if (!(curve.radius > 0.0)) fields.fail(where, "circle radius " + params[0].dump() + " must be positive");
    // SVG would silently enlarge a too-small radius; allow round-off only, reject real mistakes.
    if (curve.radius < halfChord * (1.0 - 1e-4))
      fields.fail(where, "circle radius " + params[0].dump() + " is smaller than half the edge's chord (" +
                             Json(halfChord).dump() + ")");
  } else {
    fields.fail(where, "unknown curvature type '" + type + "' (expected quadratic, cubic or circle)");
  }
  return curve;
}

}  // namespace drape::detail
