#pragma once
// Geometry of one panel edge: evaluation, length and sampling by arc length, in the panel's 2D frame.
#include <Eigen/Core>
#include <vector>

#include "drape/pattern/pattern.h"

namespace drape {

// Point on the edge at curve parameter t in [0, 1] (not arc length), file units.
Eigen::Vector2d evaluateEdge(const Panel& panel, int edge, double t);

// Arc length of the edge, file units (numerically integrated for curves).
double edgeLength(const Panel& panel, int edge);

// segments + 1 points along the edge spaced evenly by arc length, first = start vertex, last = end vertex.
std::vector<Eigen::Vector2d> sampleEdge(const Panel& panel, int edge, int segments);

// The closed outline of a panel with every edge sampled finely enough for geometric checks
// (area, self-intersection); no point is repeated.
std::vector<Eigen::Vector2d> panelOutline(const Panel& panel, double maxSegmentLength);

}  // namespace drape
