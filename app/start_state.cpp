#include "start_state.h"

#include "drape/io/garment_state.h"

namespace drape::app {

std::unique_ptr<Simulation> startSimulation(Scene scene, const std::string& from) {
  if (from.empty()) return std::make_unique<Simulation>(std::move(scene));
  return simulationFromStateFile(std::move(scene), from);
}

Eigen::MatrixX3d placedOrFrom(const Garment& garment, const std::string& from) {
  return from.empty() ? garment.positions : readGarmentPositions(from, garment);
}

}  // namespace drape::app
