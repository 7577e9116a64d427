#pragma once
// --from STATE.obj: the simulation (or, for stage none, the positions) a headless mode starts from.
#include <Eigen/Core>
#include <memory>
#include <string>

#include "drape/garment/garment.h"
#include "drape/sim/simulation.h"

namespace drape::app {

// The simulation of scene: from the placed garment when `from` is empty, else drape::simulationFromStateFile
// (throws InputError naming the file).
std::unique_ptr<Simulation> startSimulation(Scene scene, const std::string& from);

// Stage none: the placed garment's positions when `from` is empty, else drape::readGarmentPositions.
Eigen::MatrixX3d placedOrFrom(const Garment& garment, const std::string& from);

}  // namespace drape::app
