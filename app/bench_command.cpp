// drape --bench SCENE [--sweep KEY=V1,V2,...]...: the speed/accuracy trade of solver settings, measured.
// A reference drape with tight settings runs first; then every sweep value runs alone (other settings at the
// scene's values) and is reported against it: wall time (and its ratio to the reference), the mean and max
// distance of the final garment to the reference drape, the largest strain and the number of vertices inside a
// collider deeper than the contact thickness.
#include <chrono>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <ostream>

#include "commands.h"
#include "drape/collision/avatar_collider.h"
#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"
#include "drape/sim/simulation.h"
#include "drape/sim/snapshot_builder.h"
#include "scene_request.h"

namespace drape::app {
namespace {

struct RunResult {
  std::string label;
  std::string status;
  double wall = 0.0;
  double simTime = 0.0;
  int steps = 0;
  Eigen::MatrixX3d positions;
  double maxStrain = 0.0;
  int penetrations = 0;
};

RunResult runOnce(const CliOptions& options, std::vector<std::pair<std::string, std::string>> overrides,
                  const std::string& label) {
  SceneRequest request = requestWithStage(options);
  request.overrides.insert(request.overrides.end(), overrides.begin(), overrides.end());
  request.overrides.emplace_back("solver.stage", "drape");
  Scene scene = loadScene(request);
  const auto start = std::chrono::steady_clock::now();
  Simulation simulation(std::move(scene));
  RunResult r;
  r.label = label;
  StepReport last;
  while (!simulation.finished()) {
    last = simulation.step();
    if (last.status == StepStatus::Diverged || last.status == StepStatus::Cancelled) {
      r.status = toString(last.status);
      break;
    }
  }
  if (r.status.empty()) r.status = simulation.endReason();
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.simTime = simulation.time();
  r.steps = simulation.steps();
  r.positions = simulation.positions();
  r.maxStrain = last.maxStrain;
  const TriangleMesh colliders = mergedColliders(simulation.scene());
  if (colliders.triangleCount() > 0) {
    const collision::AvatarCollider collider(colliders);
    const double depth = simulation.contactThickness();
    for (int v = 0; v < r.positions.rows(); ++v)
      if (collider.signedDistance(r.positions.row(v).transpose()) < -depth) ++r.penetrations;
  }
  return r;
}

std::vector<std::string> splitCommas(const std::string& s) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= s.size()) {
    const size_t comma = s.find(',', start);
    out.push_back(s.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace

int runBench(const CliOptions& options, std::ostream& out) {
  if (options.extremes) return runExtremes(options, out);
  // Tight reference: a 4x smaller step limit and 100x tighter tolerances than the paper's defaults.
  const std::vector<std::pair<std::string, std::string>> reference = {{"solver.newton.h_max", "2.5e-4"},
                                                                      {"solver.newton.tolerance", "1e-5"},
                                                                      {"solver.cg.tolerance", "1e-4"}};
  std::vector<std::pair<std::string, std::vector<std::string>>> sweeps;
  for (const auto& s : options.sweeps) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError("--sweep: '" + s + "' is not KEY=V1,V2,...");
    sweeps.emplace_back(s.substr(0, eq), splitCommas(s.substr(eq + 1)));
  }
  if (sweeps.empty())
    sweeps = {{"solver.newton.h_max", {"1e-3", "2e-3"}},
              {"solver.cg.tolerance", {"1e-1", "1e-2"}},
              {"solver.cg.preconditioner", {"diagonal", "block_jacobi"}}};

  const RunResult ref = runOnce(options, reference, "reference");
  std::vector<RunResult> runs;
  for (const auto& [key, values] : sweeps)
    for (const auto& v : values) runs.push_back(runOnce(options, {{key, v}}, key + "=" + v));

  nlohmann::json report = {{"scene", options.scene.input.string()}, {"reference_settings", reference},
                           {"runs", nlohmann::json::array()}};
  out << std::left << std::setw(40) << "run" << std::right << std::setw(11) << "wall s" << std::setw(10) << "vs ref"
      << std::setw(12) << "mean mm" << std::setw(12) << "max mm" << std::setw(11) << "strain %" << std::setw(8)
      << "inside" << "  status\n";
  auto row = [&](const RunResult& r) {
    const Eigen::VectorXd d = (r.positions - ref.positions).rowwise().norm();
    const double mean = d.size() ? d.mean() * 1e3 : 0.0, worst = d.size() ? d.maxCoeff() * 1e3 : 0.0;
    out << std::left << std::setw(40) << r.label << std::right << std::fixed << std::setprecision(2) << std::setw(11)
        << r.wall << std::setw(9) << r.wall / ref.wall << "x" << std::setw(12) << mean << std::setw(12) << worst
        << std::setw(11) << 100 * r.maxStrain << std::setw(8) << r.penetrations << "  " << r.status << "\n"
        << std::defaultfloat;
    report["runs"].push_back({{"run", r.label}, {"wall_time_s", r.wall}, {"wall_ratio_to_reference", r.wall / ref.wall},
                              {"mean_distance_mm", mean}, {"max_distance_mm", worst}, {"max_strain", r.maxStrain},
                              {"penetrations", r.penetrations}, {"sim_time_s", r.simTime}, {"steps", r.steps},
                              {"status", r.status}});
  };
  row(ref);
  for (const auto& r : runs) row(r);
  // Distances to a reference that did not finish its drape measure nothing: say so and fail.
  const bool referenceOk = ref.status == "AtRest" || ref.status == "MaxSimTime";
  report["reference_status"] = ref.status;
  if (!options.output.empty()) writeFileAtomically(options.output, report.dump(2) + "\n");
  if (!referenceOk) {
    out << "drape --bench: the reference drape ended " << ref.status << " at t = " << ref.simTime
        << " s, so the distances above are to its last good state and not meaningful\n";
    return 1;
  }
  return 0;
}

}  // namespace drape::app
