// Input of the Newton drape solver: a cloth mesh with its rest shape in the pattern's material frame, fabric
// parameters per triangle, stitches and pins. Built by the scene (or directly by tests).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace drape::model {

// Fabric parameters of one triangle (see drape::Fabric for typical values).
struct TriangleFabric {
  double stretchWarp = 2000.0;  // N/m, along pattern x
  double stretchWeft = 2000.0;  // N/m, along pattern y
  double shear = 60.0;          // N/m
  double bendWarp = 5e-6;       // N m, folds across the warp (fold line along the weft)
  double bendWeft = 5e-6;       // N m, folds across the weft (fold line along the warp)
  double density = 0.12;        // kg/m^2
};

// A non-conforming stitch (pd-dd section 4.4): vertex pulled by a zero-length spring towards the point
// (1 - t) x_a + t x_b of the edge (a, b) of another panel, which was meshed at its own spacing. The spring has the
// stiffness of a vertex stitch; the edge need not be a mesh edge, but a, b and vertex must be distinct.
struct EdgeStitch {
  int vertex = 0;
  int a = 0;
  int b = 0;
  double t = 0.0;  // barycentric position along a -> b, in [0, 1]
};

struct ClothModel {
  Eigen::MatrixX2d restCoords;            // |V| x 2, metres, material frame (x = warp, y = weft)
  Eigen::MatrixX3i triangles;             // |T| x 3, vertex indices, counter-clockwise in restCoords
  std::vector<TriangleFabric> fabrics;    // |T| (or 1: used for every triangle)
  Eigen::VectorXd positions;              // 3|V|, metres, initial placement
  Eigen::VectorXd velocities;             // 3|V|, m/s; empty = at rest
  // Vertex pairs pulled together by zero-length springs; a pair (v, v) (a dart tip shared by both sides of its
  // seam) is allowed and ignored.
  std::vector<std::pair<int, int>> stitches;
  std::vector<EdgeStitch> edgeStitches;   // vertices pulled onto points of edges (non-conforming seams)
  std::vector<int> pinned;                // pinned vertex indices
  std::vector<Eigen::Vector3d> pinTargets;  // per pinned vertex, metres; empty = initial positions
  // Moving pins: target of pinned[k] at simulated time t (seconds, on the scene's clock), metres. Empty = every
  // pin holds its target for the whole run.
  std::function<Eigen::Vector3d(int k, double t)> pinTrajectory;
  double startTime = 0.0;  // scene time of positions/velocities, s (a drape started from the preview's state)
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, -9.81, 0.0);  // m/s^2

  int numVertices() const { return static_cast<int>(restCoords.rows()); }
  const TriangleFabric& fabric(int t) const { return fabrics.size() == 1 ? fabrics[0] : fabrics[t]; }
};

// Checks both kinds of stitch against the vertex count and throws drape::InputError naming the first bad one,
// e.g. "cloth model: edge stitch 4: t = 1.5 outside [0, 1]". context prefixes the message ("cloth model").
void validateStitches(const ClothModel& model, const std::string& context = "cloth model");

}  // namespace drape::model
