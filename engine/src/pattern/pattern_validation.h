#pragma once
// Private: checks of a parsed pattern that need its geometry: simple (non-self-intersecting) panel outlines
// with area, and stitched edges of similar length (a warning otherwise).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "drape/core/diagnostics.h"
#include "drape/pattern/pattern.h"
#include "pattern/json_fields.h"

namespace drape::detail {

// Where a closed polyline first touches or crosses itself: the two segments (indices into the polyline, segment
// k runs from point k to point k + 1 mod n) and a point near the contact.
struct OutlineContact {
  int segmentA = 0;
  int segmentB = 0;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
};

// Finds a contact between two non-adjacent segments of the closed polyline (or two adjacent segments that fold
// back onto each other), or nothing when the polyline is simple. O(n log n + candidates).
std::optional<OutlineContact> findSelfContact(const std::vector<Eigen::Vector2d>& outline);

// Signed area of a closed polyline (> 0 counter-clockwise), squared file units.
double signedArea(const std::vector<Eigen::Vector2d>& outline);

// Limits of a panel, metres and degrees (docs/FORMATS.md "Limits").
constexpr double kMinPanelArea = 1e-6;          // 1 mm^2: below, mesh triangles approach rounding error
constexpr double kMaxPanelExtent = 100.0;       // outline bounding-box diagonal
constexpr double kMaxPanelTranslation = 100.0;  // |translation| after unit conversion
constexpr double kMaxPanelRotationDeg = 360.0;  // each Euler angle

// Throws InputError naming the panel and edges when the panel outline crosses itself, encloses no area, or is
// smaller than kMinPanelArea or larger than kMaxPanelExtent (unitsInMeter: file units per metre).
void validatePanelOutline(const Panel& panel, double unitsInMeter, const JsonFields& fields);

// The closed outline with each curved edge sampled into segmentsPerCurve segments (a straight edge is one), from
// edge 0's start, no point repeated; edgeOfSegment, when given, receives the edge of each segment.
std::vector<Eigen::Vector2d> sampledOutline(const Panel& panel, int segmentsPerCurve,
                                            std::vector<int>* edgeOfSegment = nullptr);

// Throws InputError naming the panel when its translation or rotation is beyond the limits above.
void validatePanelPlacement(const Panel& panel, double unitsInMeter, const JsonFields& fields);

// Adds a warning to diagnostics for every stitch whose two edges differ in length by more than 5% (eased and gathered
// seams do), and refuses one where an edge is more than twice the other (kMaxStitchLengthRatio): that is no seam, a
// pattern error. Throws InputError naming the stitch and both edges.
inline constexpr double kMaxStitchLengthRatio = 2.0;
void checkStitchLengths(const Pattern& pattern, Diagnostics& diagnostics);

}  // namespace drape::detail
