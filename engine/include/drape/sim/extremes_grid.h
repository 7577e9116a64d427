#pragma once
// The extremes grid (`drape --bench SCENE --extremes`): every setting that shapes the physics at both ends of its own
// range (Settings::specs), and the hard combinations, run on a scene in a stage, each cell judged on what a user
// must be able to trust at the extremes: finite, not diverged (or diverged and said why), nothing inside the body
// beyond the contact thickness, and the strain bounded.
#include <string>
#include <utility>
#include <vector>

#include "drape/scene/scene.h"

namespace drape {

struct ExtremeCell {
  std::string name;  // "stretch min", "stiffest + coarsest + largest step", ...
  std::vector<std::pair<std::string, std::string>> settings;
};

// The grid's cells in order: stretch, shear, bending, density, friction, thickness, gravity, damping, mesh edge
// length, time step and the Newton and CG tolerances, each at the minimum and the maximum of its range (the mesh at
// 5 mm rather than its range's 0.1 mm, which a garment's triangle limit refuses), then softest + finest + largest
// step + strongest gravity, stiffest + coarsest + largest step, and no friction under the strongest gravity (a steep
// slope for every contact on the body).
std::vector<ExtremeCell> extremeCells();

struct ExtremeOutcome {
  std::string cell;
  std::string stage;   // "drape", "preview" or "full"
  std::string status;  // the run's end: "AtRest", "MaxSimTime", "MaxSteps", "Diverged", or "Refused" at load
  std::string divergedReason;  // Simulation::divergedReason, when the garment exploded
  std::string refusal;         // the input error that refused the cell's scene (a correct answer, not a failure)
  double wallSeconds = 0.0;
  double simTime = 0.0;
  int steps = 0;
  int vertices = 0;
  bool finite = true;          // every final position finite
  double maxStrain = 0.0;      // of the final state (triangleStretch)
  int insideVertices = 0;      // deeper inside a collider than the contact thickness
  double deepestMm = 0.0;      // the deepest vertex, mm inside (0: none inside)
  // Empty when the cell holds (finite; not diverged, or diverged with the explosion said; nothing inside beyond the
  // contact thickness); else what failed, in words.
  std::string failure;
};

// Runs one cell on the scene `base` (its settings, then the cell's, then the stage and the limits) for at most
// maxSimTime seconds and maxSteps steps.
ExtremeOutcome runExtremeCell(const SceneRequest& base, const ExtremeCell& cell, const std::string& stage,
                              double maxSimTime, int maxSteps);

}  // namespace drape
