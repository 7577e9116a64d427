#pragma once
// The settings of a simulation's stages, read once from a scene into typed structs (DESIGN.md 5b): nothing below
// the scene reads a setting by its name. The preview's defaults are the settings table's (settings_specs.cpp takes
// them from PreviewStageSettings), so each has one source.
#include "drape/newton/newton_solver.h"
#include "drape/scene/scene.h"

namespace drape {

// The preview stage: the drape's own incremental potential solved by L-BFGS whose initial Hessian is pd-dd's
// domain-decomposed system (DESIGN.md 5a), at a longer step than the drape's.
struct PreviewStageSettings {
  double timeStep = 1.0 / 120.0;  // s (pd-dd Tab. 1)
  int iterations = 4;             // L-BFGS iterations per step
  int domains = 0;                // METIS domains of the initial Hessian's solve (0: the thread count)
  double maxTime = 0.5;           // s: the longest preview of the full pipeline before the drape takes over
  double handoffSpeed = 0.1;      // m/s: the full pipeline hands over once the 99th percentile of the step's vertex
                                  // speeds stays below this for 0.1 s
  bool monolithic = false;        // implementation switch: one CHOLMOD factor instead of the domains (benchmarks)
};

// The drape stage: Backward-Euler Newton (newton-drape-pizana).
struct DrapeStageSettings {
  newton::NewtonSettings newton;
  // A drape from a preview's state: relax again (seams are already closed), and the cap on its step as a multiple of
  // newton.hMax (it starts at hMax and grows).
  bool relaxationAfterPreview = false;
  double hMaxFactorAfterPreview = 10.0;
};

// The contact terms both stages solve (contact.*).
struct ContactSettings {
  double stiffness = 1e3;         // N/m, penalty of avatar and cloth contact
  double thickness = 2e-3;        // m (contact.thickness, else the thickest fabric, at least 2 mm)
  bool avatarFeatures = true;     // the avatar's sharp points push garment triangles
  bool selfCollision = false;     // cloth-cloth contact (self_contact, intersection_contour)
  bool friction = true;           // Coulomb friction (where a fabric's coefficient is above 0)
  bool frictionMajorizer = true;  // a step's first Newton iteration takes friction's isotropic majorizer
};

struct SimulationSettings {
  StagePlan plan = StagePlan::Drape;
  double maxSimTime = 3.0;  // s of scene time (of the drape's own time for a drape resumed from a preview)
  int maxSteps = 100000;
  double gravity = -9.81;  // m/s^2 along y
  ContactSettings contact;
  PreviewStageSettings preview;
  DrapeStageSettings drape;
};

SimulationSettings simulationSettingsFrom(const Scene& scene);

// The drape's Newton settings from the scene's solver.* keys, its stretch dissipation beta_s from the fabric's damping.
newton::NewtonSettings newtonSettingsFrom(const Scene& scene);

// Contact thickness of the scene: contact.thickness if set, else the thickest fabric's thickness, at least 2 mm.
double contactThickness(const Scene& scene);

}  // namespace drape
