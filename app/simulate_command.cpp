// drape --simulate SCENE -o OUT: build the garment, run the chosen solver stage, write the result.
#include <chrono>
#include <nlohmann/json.hpp>
#include <ostream>

#include "commands.h"
#include "drape/core/input_error.h"
#include "drape/garment/garment_builder.h"
#include "drape/io/atomic_file.h"
#include "drape/io/mesh_export.h"
#include "drape/scene/pins.h"

namespace drape::app {

int runSimulate(const CliOptions& options, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  if (options.solver != "none")
    throw InputError("--solver " + options.solver + ": not available yet (only 'none', the placed garment)");
  const Scene scene = loadScene(options.scene);
  Diagnostics diagnostics;
  const Garment garment =
      buildGarment(scene.pattern, MeshingOptions{scene.settings.number("mesh.target_edge_length")}, &diagnostics);
  const auto pinned = resolvePins(scene, garment);
  exportGarment(garment, garment.positions, options.output);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out << "wrote " << options.output << " (" << garment.vertexCount() << " vertices, " << garment.triangleCount()
      << " triangles, placed garment) in " << wall << " s\n";
  if (!options.stats.empty()) {
    nlohmann::json stats = {{"status", "Placed"},      {"solver", options.solver},
                            {"wall_time_s", wall},     {"sim_time_s", 0.0},
                            {"steps", 0},              {"terms", nlohmann::json::array()},
                            {"per_step", nlohmann::json::array()},
                            {"vertices", garment.vertexCount()}, {"triangles", garment.triangleCount()},
                            {"pinned_vertices", pinned.size()}};
    auto warnings = scene.diagnostics.warnings();
    warnings.insert(warnings.end(), diagnostics.warnings().begin(), diagnostics.warnings().end());
    stats["warnings"] = warnings;
    writeFileAtomically(options.stats, stats.dump(2) + "\n");
  }
  return 0;
}

}  // namespace drape::app
