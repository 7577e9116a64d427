#pragma once
// --from STATE.obj: the simulation (or, for stage none, the positions) a headless mode starts from.
#include <Eigen/Core>
#include <memory>
#include <string>

#include "drape/garment/garment.h"
#include "drape/sim/simulation.h"

namespace drape::app {

// The simulation of scene, starting at the vertex positions of `from` when it is not empty (drape::startStateAt).
// Throws InputError naming the file when it cannot be read, belongs to another garment (checkGarmentState), or
// the stage cannot start from it (a drape from a state stretched past solver.preview.failure_strain).
std::unique_ptr<Simulation> startSimulation(Scene scene, const std::string& from);

// Stage none: the positions of `from` (checked against garment), or the placed garment's when it is empty.
Eigen::MatrixX3d placedOrFrom(const Garment& garment, const std::string& from);

}  // namespace drape::app
