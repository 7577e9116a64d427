#include "drape/scene/stage_settings.h"

#include <algorithm>

namespace drape {

SimulationSettings simulationSettingsFrom(const Scene& scene) {
  const Settings& s = scene.settings;
  SimulationSettings out;
  out.plan = s.stagePlan();
  out.maxSimTime = s.number("solver.max_sim_time");
  out.maxSteps = s.integer("solver.max_steps");
  out.gravity = s.number("sim.gravity");
  out.contact.stiffness = s.number("contact.stiffness");
  out.contact.thickness = contactThickness(scene);
  out.contact.avatarFeatures = s.flag("contact.avatar_features");
  out.contact.selfCollision = s.flag("contact.self_collision");
  out.contact.friction = s.flag("contact.friction");
  out.contact.frictionMajorizer = s.flag("contact.friction_majorizer");
  PreviewStageSettings& p = out.preview;
  p.timeStep = s.number("solver.preview.time_step");
  p.iterations = s.integer("solver.preview.iterations");
  p.domains = s.integer("solver.preview.domains");
  p.maxTime = s.number("solver.preview.max_time");
  p.handoffSpeed = s.number("solver.preview.handoff_speed");
  p.monolithic = scene.implementation.monolithicGlobalSolve;
  DrapeStageSettings& d = out.drape;
  d.newton = newtonSettingsFrom(scene);
  d.relaxationAfterPreview = s.flag("solver.newton.relaxation_after_preview");
  d.hMaxFactorAfterPreview = s.number("solver.newton.h_max_factor_after_preview");
  return out;
}

newton::NewtonSettings newtonSettingsFrom(const Scene& scene) {
  const Settings& s = scene.settings;
  newton::NewtonSettings n;
  n.tauNewton = s.number("solver.newton.tolerance");
  n.maxNewtonIterations = s.integer("solver.newton.max_iterations");
  n.maxLineSearchIterations = s.integer("solver.newton.line_search_iterations");
  n.hMax = s.number("solver.newton.h_max");
  n.omega = s.number("solver.newton.omega");
  n.growAfterSteps = s.integer("solver.newton.grow_after_steps");
  n.relaxation = s.flag("solver.newton.relaxation");
  n.relaxationHoldStep = s.text("solver.newton.relaxation_step") == "hold";
  n.relaxationGuess = s.flag("solver.newton.relaxation_guess");
  n.restSpeed = s.number("solver.newton.rest_speed");
  n.restForce = s.number("solver.newton.rest_force");
  n.earlyStopWindow = s.number("solver.newton.early_stop_window");
  n.restAwareConvergence = s.flag("solver.newton.rest_aware_convergence");
  n.linear.tolerance = s.number("solver.cg.tolerance");
  n.cgForcing = s.number("solver.cg.forcing");
  n.linear.maxIterations = s.integer("solver.cg.max_iterations");
  n.linear.mixedPrecision = s.flag("solver.cg.mixed_precision");
  n.linear.warmStart = s.flag("solver.cg.warm_start");
  n.linear.fusedKernels = scene.implementation.fusedKernels;
  n.coarseAggregate = static_cast<int>(s.integer("solver.cg.coarse_aggregate"));
  n.coarseFromIterations = static_cast<int>(s.integer("solver.cg.coarse_from_iterations"));
  n.coarseLagged = s.flag("solver.cg.coarse_lagged");
  n.coupledThreshold = s.number("solver.cg.coupled_groups");
  n.coupledFromIterations = static_cast<int>(s.integer("solver.cg.coupled_from_iterations"));
  n.reorderDofs = scene.implementation.reorderDofs;
  n.closedFormBending = scene.implementation.closedFormBending;
  n.cachedBlockMap = scene.implementation.blockMap;
  n.parallelAssembly = scene.implementation.parallelAssembly;
  n.foldDissipation = scene.implementation.foldDissipation;
  n.batchedGradients = scene.implementation.batchedGradients;
  n.hessianReuseSteps = s.integer("solver.newton.hessian_reuse_steps");
  // The choices of solver.cg.preconditioner are newton::Preconditioner's, then cholmod_direct (no PCG).
  if (s.text("solver.cg.preconditioner") == "cholmod_direct") {
    n.linear.kind = newton::LinearSolverKind::Cholmod;
  } else {
    n.linear.kind = newton::LinearSolverKind::Pcg;
    n.linear.preconditioner = s.choice<newton::Preconditioner>("solver.cg.preconditioner");
  }
  n.alpha = s.number("solver.damping.air");
  // The fabric's damping is the stretch dissipation beta_s (assets/fabrics/README.md); with panels of several
  // fabrics, the largest (as friction: one coefficient for the scene).
  n.betaStretch = scene.fabric.damping;
  for (const auto& [panel, fabric] : scene.panelFabrics) n.betaStretch = std::max(n.betaStretch, fabric.damping);
  n.betaBend = s.number("solver.damping.bend");
  n.stitchStiffness = s.number("solver.stitch_stiffness");
  n.pinStiffness = s.number("solver.pin_stiffness");
  return n;
}

double contactThickness(const Scene& scene) {
  if (scene.settings.has("contact.thickness")) return scene.settings.number("contact.thickness");
  double t = scene.fabric.thickness;
  for (const auto& [panel, fabric] : scene.panelFabrics) t = std::max(t, fabric.thickness);
  return std::max(t, 2e-3);
}

}  // namespace drape
