// drape --bench SCENE --extremes: the extremes grid (drape/sim/extremes_grid.h) on one scene, one line per cell and
// stage as it finishes, then a JSON report (-o). Each run has at most --max-sim-time (0.5 s) simulated and
// kMaxSteps steps, so that the smallest time step in its range ends at the step limit instead of running for hours.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>

#include "commands.h"
#include "drape/io/atomic_file.h"
#include "drape/sim/extremes_grid.h"

namespace drape::app {
namespace {

constexpr int kMaxSteps = 2000;
constexpr double kDefaultSimTime = 0.5;

}  // namespace

int runExtremes(const CliOptions& options, std::ostream& out) {
  const std::vector<std::string> stages =
      options.solver.empty() ? std::vector<std::string>{"drape", "preview", "full"}
                             : std::vector<std::string>{options.solver};
  const double simTime = options.maxSimTime > 0.0 ? options.maxSimTime : kDefaultSimTime;
  std::vector<ExtremeCell> cells = extremeCells();
  if (!options.cells.empty())  // names checked by the option parser
    std::erase_if(cells, [&](const ExtremeCell& c) {
      return std::find(options.cells.begin(), options.cells.end(), c.name) == options.cells.end();
    });
  const size_t total = cells.size() * stages.size();
  nlohmann::json report = {{"scene", options.scene.input.string()},
                           {"max_sim_time_s", simTime},
                           {"max_steps", kMaxSteps},
                           {"cells", nlohmann::json::array()}};
  const auto start = std::chrono::steady_clock::now();
  size_t done = 0, failed = 0;
  char line[512];
  std::snprintf(line, sizeof line, "%-52s %-8s %-10s %9s %7s %6s %9s %8s %8s  %s\n", "cell", "stage", "status", "sim s",
                "steps", "wall s", "strain %", "inside", "deep mm", "verdict");
  out << line;
  for (const ExtremeCell& cell : cells) {
    for (const std::string& stage : stages) {
      const ExtremeOutcome o = runExtremeCell(options.scene, cell, stage, simTime, kMaxSteps);
      ++done;
      failed += !o.failure.empty();
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const std::string verdict = !o.failure.empty()        ? o.failure
                                  : !o.refusal.empty()        ? "holds: refused: " + o.refusal
                                  : !o.divergedReason.empty() ? std::string("holds: diverged, said why")
                                                              : std::string("holds");
      std::snprintf(line, sizeof line, "%-52s %-8s %-10s %9.4f %7d %6.1f %9.1f %8d %8.1f  %s  [%zu/%zu, %.0f s, about %.0f s left]\n",
                    o.cell.c_str(), o.stage.c_str(), o.status.c_str(), o.simTime, o.steps, o.wallSeconds,
                    100.0 * o.maxStrain, o.insideVertices, o.deepestMm,
                    verdict.c_str(),
                    done, total, elapsed, elapsed / done * (total - done));
      out << line << std::flush;
      nlohmann::json settings = nlohmann::json::object();
      for (const auto& [k, v] : cell.settings) settings[k] = v;
      report["cells"].push_back({{"cell", o.cell},
                                 {"settings", settings},
                                 {"stage", o.stage},
                                 {"status", o.status},
                                 {"diverged_reason", o.divergedReason},
                                 {"refusal", o.refusal},
                                 {"sim_time_s", o.simTime},
                                 {"steps", o.steps},
                                 {"vertices", o.vertices},
                                 {"wall_time_s", o.wallSeconds},
                                 {"finite", o.finite},
                                 {"max_strain", o.maxStrain},
                                 {"inside_vertices", o.insideVertices},
                                 {"deepest_mm", o.deepestMm},
                                 {"holds", o.failure.empty()},
                                 {"failure", o.failure}});
    }
  }
  report["failed_cells"] = failed;
  if (!options.output.empty()) writeFileAtomically(options.output, report.dump(2) + "\n");
  out << "drape --bench --extremes: " << total - failed << " of " << total << " cells hold\n";
  return failed == 0 ? 0 : 1;
}

}  // namespace drape::app
