#pragma once
// Geometry of one panel edge: evaluation, length and sampling by arc length, in the panel's 2D frame.
// Relative control point [x, y] of an edge from S to E -> absolute point S + x (E - S) + y n, where
// n = (-(E - S).y, (E - S).x) is the chord turned 90 degrees counter-clockwise (y > 0: left of S -> E).
// Circle: SVG arc, right = true puts the arc right of S -> E (centre to the left); docs/FORMATS.md.
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

// The closed outline of a panel with every edge (straight ones too) sampled evenly by arc length into
// segments no longer than maxSegmentLength (file units; <= 0: one segment per edge), for geometric checks
// (area, self-intersection). Starts at edge 0's start vertex; no point is repeated (the closing segment
// from the last point back to the first is implied).
std::vector<Eigen::Vector2d> panelOutline(const Panel& panel, double maxSegmentLength);

}  // namespace drape
