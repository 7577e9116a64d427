// Input of the Newton drape solver: a cloth mesh with its rest shape in the pattern's material frame, fabric
// parameters per triangle, stitches and pins. Built by the scene (or directly by tests).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <utility>
#include <vector>

namespace drape::newton {

// Fabric parameters of one triangle (see drape::Fabric for typical values).
struct TriangleFabric {
  double stretchWarp = 2000.0;  // N/m, along pattern x
  double stretchWeft = 2000.0;  // N/m, along pattern y
  double shear = 60.0;          // N/m
  double bendWarp = 5e-6;       // N m, folds across the warp (fold line along the weft)
  double bendWeft = 5e-6;       // N m, folds across the weft (fold line along the warp)
  double density = 0.12;        // kg/m^2
};

struct ClothModel {
  Eigen::MatrixX2d restCoords;            // |V| x 2, metres, material frame (x = warp, y = weft)
  Eigen::MatrixX3i triangles;             // |T| x 3, vertex indices, counter-clockwise in restCoords
  std::vector<TriangleFabric> fabrics;    // |T| (or 1: used for every triangle)
  Eigen::VectorXd positions;              // 3|V|, metres, initial placement
  Eigen::VectorXd velocities;             // 3|V|, m/s; empty = at rest
  std::vector<std::pair<int, int>> stitches;  // vertex pairs pulled together by zero-length springs
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

}  // namespace drape::newton
