#pragma once
// One stage of a simulation (DESIGN.md 5b): the preview, the drape, or a later one. A Simulation holds one stage at a
// time and hands over between stages through the state alone (positions, velocities, scene time); each stage reads
// its settings once, from its own typed struct (scene/stage_settings.h). Private to the engine.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "drape/sim/simulation.h"

namespace drape {

class StageSolver {
 public:
  virtual ~StageSolver() = default;

  // Preview or Drape: what the stage shows to the statistics, the GUI and the hand-over.
  virtual Stage stage() const = 0;
  // Advances one step. Fills the report's solver fields (status, stage, time, h, iterations, residual, kinetic
  // energy, contacts, phase times, atRest); the Simulation adds the strain and the wall time.
  virtual StepReport step() = 0;

  virtual const Eigen::VectorXd& positions() const = 0;   // 3|V|, metres
  virtual const Eigen::VectorXd& velocities() const = 0;  // 3|V|, m/s
  virtual double time() const = 0;                        // scene time, s
  // The stage's own test that the garment is at rest (it stays so until a drag or a new stage).
  virtual bool atRest() const = 0;

  // A grabbed vertex pulled towards target (metres) by a spring; vertex < 0 releases it.
  virtual void setDrag(int vertex, const Eigen::Vector3d& target) = 0;
  virtual void requestCancel() = 0;
  virtual void clearCancel() = 0;

  // The names of the terms the stage solves ("membrane", "bending", "avatar_contact", ...).
  virtual std::vector<std::string> terms() const = 0;
  // |V| mask, 1 where a vertex is within 1.5 contact thicknesses of a collider (for snapshots).
  virtual Eigen::VectorXi contactMask() const = 0;
  // The domain of each garment triangle where the stage decomposes the garment; no rows where it does not.
  virtual Eigen::VectorXi triangleDomains() const { return {}; }
};

}  // namespace drape
