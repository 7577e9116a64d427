// drape --simulate SCENE -o OUT: build the garment, run the chosen solver stage, write the result and statistics.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>

#include "commands.h"
#include "drape/core/input_error.h"
#include "drape/io/atomic_file.h"
#include "drape/io/mesh_export.h"
#include "drape/scene/pins.h"
#include "drape/sim/scene_garment.h"
#include "drape/sim/simulation.h"
#include "drape/sim/snapshot_builder.h"
#include "profile_json.h"
#include "quality_output.h"
#include "scene_request.h"
#include "start_state.h"

namespace drape::app {
namespace {

nlohmann::json stepRecord(const StepReport& r) {
  nlohmann::json j = {{"stage", stageName(r.stage)},
                      {"time", r.time},
                      {"h", r.h},
                      {"status", toString(r.status)},
                      {"iterations", r.iterations},
                      {"cg_iterations", r.cgIterations},
                      {"splits", r.splits},
                      {"residual", r.residual},
                      {"kinetic_energy_p99", r.kineticEnergy},
                      {"contacts", r.contacts},
                      {"feature_contacts", r.featureContacts},
                      {"max_strain", r.maxStrain},
                      {"max_strain_triangle", r.maxStrainTriangle},
                      {"force_rms", r.forceRms},
                      {"force_max", r.forceMax},
                      {"displacement_max_m", r.displacementMax},
                      {"contact_query_time_s", r.contactQueryTime},
                      {"wall_time_s", r.wallTime}};
  if (r.quasiNewton) {  // the preview's L-BFGS steps: iterations are its iterations
    j["quasi_newton"] = true;
    j["domains"] = r.domains;
    j["line_search_evaluations"] = r.lineSearchEvaluations;
    j["preconditioner_time_s"] = r.assemblyTime;
    j["gradient_time_s"] = r.gradientTime;
    j["direction_time_s"] = r.linearSolveTime;
  } else {
    j["assembly_time_s"] = r.assemblyTime;
    j["gradient_time_s"] = r.gradientTime;
    j["linear_solve_time_s"] = r.linearSolveTime;
    j["hessian_reused"] = r.hessianReused;
    j["coarse_solves"] = r.coarseSolves;
    j["coarse_factorizations"] = r.coarseFactorizations;
    j["coupled_solves"] = r.coupledSolves;
  }
  return j;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int runSimulate(const CliOptions& options, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  if (!options.png.empty()) checkPngPath(options.png, "--png");
  // Fail before a long drape, not after it, when an output cannot be written.
  for (const std::string& file : {options.output, options.stats, options.png})
    if (!file.empty()) checkWritableDirectory(file);
  Scene scene = loadScene(requestWithStage(options));
  const SceneCamera camera = sceneCamera(scene.settings);
  const std::string stage = scene.settings.text("solver.stage");
  nlohmann::json stats;
  std::vector<std::string> warnings;
  int exitStatus = 0;

  if (scene.settings.stagePlan() == StagePlan::None) {
    Diagnostics diagnostics;
    const Garment garment = buildSceneGarment(scene, &diagnostics);
    const auto pinned = resolvePins(scene, garment);
    warnings = scene.diagnostics.warnings();
    warnings.insert(warnings.end(), diagnostics.warnings().begin(), diagnostics.warnings().end());
    printWarnings(warnings, out);
    const Eigen::MatrixX3d positions = placedOrFrom(garment, options.from);
    exportGarment(garment, positions, options.output);
    if (!options.png.empty()) renderToPng(makeSnapshot(scene, garment, positions), options, camera, options.png, out);
    stats = {{"status", options.from.empty() ? "Placed" : "FromState"},
             {"steps", 0},
             {"sim_time_s", 0.0},
             {"terms", nlohmann::json::array()},
             {"per_step", nlohmann::json::array()},
             {"vertices", garment.vertexCount()},
             {"triangles", garment.triangleCount()},
             {"pinned_vertices", pinned.size()}};
    out << "wrote " << options.output << " (" << garment.vertexCount() << " vertices, " << garment.triangleCount()
        << " triangles, " << (options.from.empty() ? "placed garment" : "the state of " + options.from) << ")\n";
  } else {
    const std::unique_ptr<Simulation> started = startSimulation(std::move(scene), options.from);
    Simulation& simulation = *started;
    if (!options.from.empty()) out << "starting the " << stage << " stage from " << options.from << "\n";
    warnings = simulation.scene().diagnostics.warnings();  // the scene's and the garment mesher's
    printWarnings(warnings, out);
    const auto terms = simulation.terms();
    out << "drape: " << simulation.garment().vertexCount() << " vertices, " << simulation.garment().triangleCount()
        << " triangles; terms:";
    for (const auto& t : terms) out << " " << t;
    out << "\n";
    nlohmann::json perStep = nlohmann::json::array();
    int domains = 0;
    Stage lastStage = simulation.stage();
    std::string status;       // Diverged or Cancelled from a step, else why the run finished
    double nextPrint = 0.0, nextWallPrint = 5.0;
    const double maxSimTime = simulation.settings().maxSimTime;
    StepReport last;
    while (!simulation.finished()) {
      last = simulation.step();
      perStep.push_back(stepRecord(last));
      domains = std::max(domains, last.domains);
      if (simulation.stage() != lastStage) {
        out << "  stage " << lastStage << " -> " << simulation.stage() << " at t=" << last.time << " s\n";
        lastStage = simulation.stage();
      }
      if (last.status == StepStatus::Diverged || last.status == StepStatus::Cancelled) {
        status = toString(last.status);
        break;
      }
      // A progress line every 0.1 s simulated, and at least every 5 s of wall time, so that a slow drape (a stiff
      // fabric, a fine mesh) is never silent: steps and wall time so far and, from the rate so far, at most how long
      // the rest of solver.max_sim_time takes (the early stop may come sooner).
      const double wall = secondsSince(start);
      if (last.time >= nextPrint || wall >= nextWallPrint) {
        char estimate[64] = "";
        if (last.time >= 0.05 * maxSimTime)  // the first steps' rate says little about the rest
          std::snprintf(estimate, sizeof estimate, "  left<=%.0f s",
                        wall / last.time * std::max(0.0, maxSimTime - last.time));
        // The preview's iterations are L-BFGS iterations; its line searches evaluate the potential.
        char work[80];
        if (last.quasiNewton)
          std::snprintf(work, sizeof work, "lbfgs=%d  evaluations=%d", last.iterations, last.lineSearchEvaluations);
        else
          std::snprintf(work, sizeof work, "iterations=%d  cg=%d", last.iterations, last.cgIterations);
        char line[280];
        std::snprintf(line, sizeof line,
                      "  %s t=%.3f s  step=%d  h=%.2e  %s  residual=%.2e  KE=%.2e  contacts=%d  wall=%.1f s%s\n",
                      stageName(last.stage), last.time, simulation.steps(), last.h, work, last.residual,
                      last.kineticEnergy, last.contacts, wall, estimate);
        out << line << std::flush;
        nextPrint = last.time + 0.1;
        nextWallPrint = wall + 5.0;
      }
    }
    if (status.empty()) status = simulation.endReason();
    exportGarment(simulation.garment(), simulation.positions(), options.output);
    if (!options.png.empty()) renderToPng(simulation.snapshot(), options, camera, options.png, out);
    stats = {{"status", status},
             {"steps", simulation.steps()},
             {"sim_time_s", simulation.time()},
             {"terms", terms},
             {"per_step", perStep},
             {"vertices", simulation.garment().vertexCount()},
             {"triangles", simulation.garment().triangleCount()},
             {"pinned_vertices", simulation.pinned().size()},
             {"final", stepRecord(last)},
             {"profile", profileJson(simulation.profile())},
             {"domains", domains}};
    if (!simulation.divergedReason().empty()) stats["diverged_reason"] = simulation.divergedReason();
    out << simulation.stage() << ": " << status << " after " << simulation.steps() << " steps, " << simulation.time()
        << " s simulated; wrote " << options.output << "\n";
    if (status == "Diverged")
      out << "drape: the " << last.stage << " diverged at t=" << last.time << " s"
          << (simulation.divergedReason().empty() ? "" : ": " + simulation.divergedReason())
          << "; the last good state was written\n";
    const QualityReport quality = checkDrapeQuality(simulation, status);
    printQualityWarnings(quality, out);
    stats["quality"] = qualityJson(quality);
    exitStatus = simulatedExitStatus(status, quality);
  }
  const double wall = secondsSince(start);
  stats["wall_time_s"] = wall;
  stats["solver"] = stage;
  if (!options.from.empty()) stats["from"] = options.from;
  stats["warnings"] = warnings;
  if (!options.stats.empty()) writeFileAtomically(options.stats, stats.dump(2) + "\n");
  return exitStatus;
}

}  // namespace drape::app
