#include "sim/cloth_model_builder.h"

#include <algorithm>
#include <optional>

#include "drape/scene/pins.h"

namespace drape {
namespace {

model::TriangleFabric toTriangleFabric(const Fabric& f) {
  model::TriangleFabric t;
  t.stretchWarp = f.stretchWarp;
  t.stretchWeft = f.stretchWeft;
  t.shear = f.shear;
  t.bendWarp = f.bendWarp;
  t.bendWeft = f.bendWeft;
  t.density = f.density;
  return t;
}

}  // namespace

model::ClothModel buildClothModel(const Scene& scene, const Garment& garment, const std::vector<int>& pinned) {
  model::ClothModel model;
  model.restCoords = garment.rest;
  model.triangles = garment.triangles;
  // One fabric entry per panel, expanded per triangle only when panels differ.
  std::vector<model::TriangleFabric> perPanel;
  bool uniform = true;
  for (const auto& name : garment.panelNames) {
    perPanel.push_back(toTriangleFabric(scene.fabricOfPanel(name)));
    uniform = uniform && scene.panelFabrics.count(name) == 0;
  }
  if (uniform) {
    model.fabrics = {toTriangleFabric(scene.fabric)};
  } else {
    model.fabrics.resize(garment.triangleCount());
    for (int t = 0; t < garment.triangleCount(); ++t) model.fabrics[t] = perPanel[garment.trianglePanel[t]];
  }
  model.positions.resize(3 * garment.vertexCount());
  for (int v = 0; v < garment.vertexCount(); ++v) model.positions.segment<3>(3 * v) = garment.positions.row(v);
  model.stitches = garment.stitchPairs;
  for (const GarmentEdgeStitch& e : garment.edgeStitches) model.edgeStitches.push_back({e.vertex, e.a, e.b, e.t});
  model.pinned = pinned;
  // Moving pins: each follows its pin's motion from where the garment places it.
  const std::vector<int> motionOf = pinMotionIndex(scene, garment, pinned);
  if (std::any_of(motionOf.begin(), motionOf.end(), [](int m) { return m >= 0; })) {
    std::vector<std::optional<PinMotion>> motions(pinned.size());
    std::vector<Eigen::Vector3d> initial(pinned.size());
    for (size_t k = 0; k < pinned.size(); ++k) {
      initial[k] = garment.positions.row(pinned[k]).transpose();
      if (motionOf[k] >= 0) motions[k] = scene.pins[motionOf[k]].motion;
    }
    model.pinTrajectory = [motions, initial](int k, double t) -> Eigen::Vector3d {
      return motions[k] ? motions[k]->at(initial[k], t) : initial[k];
    };
  }
  model.gravity = Eigen::Vector3d(0.0, scene.settings.number("sim.gravity"), 0.0);
  return model;
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

pd::PreviewSettings previewSettingsFrom(const Scene& scene) {
  const Settings& s = scene.settings;
  pd::PreviewSettings p;
  p.timeStep = s.number("solver.preview.time_step");
  p.tolerance = s.number("solver.preview.tolerance");
  p.maxIterations = s.integer("solver.preview.max_iterations");
  p.andersonWindow = s.integer("solver.preview.anderson_window");
  p.maxHalvings = s.integer("solver.preview.max_halvings");
  p.growAfterSteps = s.integer("solver.preview.grow_after_steps");
  p.domains = s.integer("solver.preview.domains");
  p.localStep = s.choice<pd::LocalStepKind>("solver.preview.local_step");
  p.globalSolver = scene.implementation.monolithicGlobalSolve ? pd::GlobalSolverKind::Monolithic
                                                              : pd::GlobalSolverKind::DomainDecomposed;
  p.contactSolve = s.choice<pd::ContactSolveKind>("solver.preview.contact_solve");
  p.pcgTolerance = s.number("solver.preview.pcg_tolerance");
  p.holdContactTargets = s.flag("solver.preview.hold_contact_targets");
  p.holdTargetsStep = s.number("solver.preview.hold_targets_step");
  p.sewnGap = s.number("solver.preview.sewn_gap");
  p.sewnTime = s.number("solver.preview.sewn_time");
  p.sewnLocalStep = s.choice<pd::LocalStepKind>("solver.preview.sewn_local_step");
  p.contactTargets = s.choice<pd::ContactTargetKind>("solver.preview.contact_targets");
  p.frictionLoad = s.choice<pd::FrictionLoadKind>("solver.preview.friction_load");
  p.shearModel = s.choice<pd::ShearModelKind>("solver.preview.shear_model");
  p.relaxationTime = s.number("solver.preview.relaxation_time");
  p.courantLimit = s.number("solver.preview.courant_limit");
  p.contactThickness = contactThickness(scene);
  p.sdIterations = s.integer("solver.preview.sd_iterations");
  p.ccd = s.flag("solver.preview.ccd");
  p.selfCollision = s.flag("contact.self_collision");
  if (s.flag("contact.friction")) {  // as the drape: the largest coefficient of the scene's fabrics
    p.friction = scene.fabric.friction;
    for (const auto& [panel, fabric] : scene.panelFabrics) p.friction = std::max(p.friction, fabric.friction);
  }
  return p;
}

double contactThickness(const Scene& scene) {
  if (scene.settings.has("contact.thickness")) return scene.settings.number("contact.thickness");
  double t = scene.fabric.thickness;
  for (const auto& [panel, fabric] : scene.panelFabrics) t = std::max(t, fabric.thickness);
  return std::max(t, 2e-3);
}

}  // namespace drape
