#include "start_state.h"

#include "drape/core/input_error.h"
#include "drape/io/garment_state.h"

namespace drape::app {

std::unique_ptr<Simulation> startSimulation(Scene scene, const std::string& from) {
  if (from.empty()) return std::make_unique<Simulation>(std::move(scene));
  const GarmentState state = readGarmentState(from);  // before the garment is meshed: a bad file fails at once
  const std::string stage = scene.settings.text("solver.stage");
  auto simulation = std::make_unique<Simulation>(std::move(scene), startStateAt(stage, state.positions));
  checkGarmentState(state, simulation->garment(), from);
  if (!simulation->resumed()) {
    const std::string why = simulation->previewFailure();
    throw InputError(from + ": " + (why.empty() ? "the " + stage + " stage cannot start from this state" : why));
  }
  return simulation;
}

Eigen::MatrixX3d placedOrFrom(const Garment& garment, const std::string& from) {
  if (from.empty()) return garment.positions;
  const GarmentState state = readGarmentState(from);
  checkGarmentState(state, garment, from);
  return state.positions;
}

}  // namespace drape::app
