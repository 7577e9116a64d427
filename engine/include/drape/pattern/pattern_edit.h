#pragma once
// Edits of a sewing pattern, as the pattern view makes them: each returns the edited copy and leaves its input
// alone. Indices follow the edit (a vertex inserted after vertex i becomes i + 1, and the edges and stitches after it
// shift with it). An edit that cannot be made as asked throws InputError naming the panel and the element, e.g.
// "shirt.json: panel 'front' edge 2 is sewn (seam 4): unpick the seam before splitting the edge". Whether the result
// is a valid pattern (outline crossing itself, seam lengths) is the loader's to say: validatedPattern.
#include <Eigen/Core>

#include "drape/core/diagnostics.h"
#include "drape/pattern/pattern.h"

namespace drape {

// Moves outline vertex `vertex` of `panel` to `to` (file units, the panel's frame). Curved edges at it keep their
// relative control points, so they follow.
Pattern moveVertex(const Pattern& pattern, int panel, int vertex, const Eigen::Vector2d& to);

// Moves control point `control` of a quadratic or cubic edge to the absolute point `to` (file units).
Pattern moveControlPoint(const Pattern& pattern, int panel, int edge, int control, const Eigen::Vector2d& to);

// Splits edge `edge` at curve parameter t in (0, 1) with a new vertex; a curve is split exactly into two curves of
// its kind. A sewn edge is refused: a seam joins two whole edges.
Pattern insertVertex(const Pattern& pattern, int panel, int edge, double t);

// Removes outline vertex `vertex`, joining its two edges into one straight edge. Refused when either edge is sewn
// or when the panel would keep fewer than three vertices.
Pattern deleteVertex(const Pattern& pattern, int panel, int vertex);

// Sews two edges face to face (Stitch::rightWrong false). Refused for an edge already sewn or for an edge sewn to
// itself.
Pattern sewEdges(const Pattern& pattern, const StitchSide& a, const StitchSide& b);

// Removes seam `stitch`.
Pattern unpickSeam(const Pattern& pattern, int stitch);

// The seam that sews edge `edge` of `panel`, or -1.
int seamOfEdge(const Pattern& pattern, int panel, int edge);

// The pattern as the loader sees it after writing it out: the same checks and the same messages as opening the
// file (outlines that cross themselves, seams of too different length become warnings in diagnostics). Throws
// InputError.
Pattern validatedPattern(const Pattern& pattern, Diagnostics* diagnostics = nullptr);

}  // namespace drape
