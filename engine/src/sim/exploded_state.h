// An exploded state: what no fabric holds together and no scene carries a garment to, so that a run in that state
// ends Diverged rather than at rest or at its time limit.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "drape/garment/garment.h"

namespace drape {

// A triangle stretched past this strain (sides 101 times their rest length) is not cloth any more: woven fabrics tear
// below 0.5, knits below 10, and the closing of a seam overshoots far less.
constexpr double kExplodedStrain = 100.0;
// A vertex farther outside the scene's box than this many of its diagonals (beyond the distance gravity alone
// carries it in the time simulated) has left the scene.
constexpr double kExplodedSceneSizes = 100.0;

// Why the state is exploded, in one line naming the triangle or vertex and its panel; empty when it is not.
// x: |V| x 3 positions (metres); stretch: per-triangle strain at x (triangleStretch); sceneBox: the colliders and the
// placed garment; gravity: |g| (m/s^2); time: simulated seconds so far.
std::string explodedReason(const Garment& garment, const Eigen::MatrixX3d& x, const Eigen::VectorXd& stretch,
                           const Eigen::AlignedBox3d& sceneBox, double gravity, double time);

}  // namespace drape
