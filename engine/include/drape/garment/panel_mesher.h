#pragma once
// Quality triangulation of one flat panel (CGAL 2D constrained Delaunay mesher) whose boundary is given as
// a closed polyline. Boundary points are kept exactly and never split, so stitched edges sampled with the
// same number of points on both sides stay paired vertex for vertex.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace drape {

struct PanelMesh {
  Eigen::MatrixX2d vertices;   // |V| x 2; the first boundary.size() rows are the boundary points, in order
  Eigen::MatrixX3i triangles;  // |F| x 3, counter-clockwise
};

// boundary: closed loop (last point not repeated), either orientation; targetEdgeLength in the same units.
// The boundary should already be sampled at about targetEdgeLength: the mesher inserts interior points only
// (refining to longest edge <= 1.3 x target and smallest angle >= ~25 degrees where the fixed boundary allows)
// and skips refinement points that would encroach a boundary segment.
// Throws InputError (with context as the message prefix) for fewer than 3 points, non-finite points or
// target, zero area, a self-intersecting or self-touching boundary, or an estimated triangle count above
// 5 million (too small a target).
PanelMesh meshPanel(const std::vector<Eigen::Vector2d>& boundary, double targetEdgeLength,
                    const std::string& context);

}  // namespace drape
