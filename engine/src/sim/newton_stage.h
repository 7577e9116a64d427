#pragma once
// A stage that solves the drape's own model (newton/): the Backward-Euler incremental potential with the scene's
// membrane, bending, stitches, pins, gravity, damping and contact. How each step's system is solved is the strategy
// passed in: Newton's own linear solve (the drape), or L-BFGS with an initial Hessian such as pd-dd's
// domain-decomposed system (the preview). Private to the engine.
#include <memory>

#include "drape/model/step_preconditioner.h"
#include "drape/newton/newton_solver.h"
#include "sim/contact_terms.h"
#include "sim/stage_solver.h"

namespace drape {

// Where a stage starts: the garment's positions and velocities (3|V|; velocities empty: at rest) at scene time `time`.
struct StageStart {
  Eigen::VectorXd positions;
  Eigen::VectorXd velocities;
  double time = 0.0;
};

// The quasi-Newton step's initial Hessian and its iterations; no preconditioner: Newton's own solve.
struct QuasiNewtonStrategy {
  std::shared_ptr<model::StepPreconditioner> preconditioner;
  newton::QuasiNewtonSettings settings;
  int domains = 0;                  // the preconditioner's domain count (statistics)
  std::vector<int> triangleDomain;  // its domain of each garment triangle (snapshots)
};

class NewtonStage final : public StageSolver {
 public:
  // model: the garment's cloth model, its positions, velocities and startTime set from where the stage starts.
  NewtonStage(Stage stage, model::ClothModel model, const newton::NewtonSettings& settings, ContactTerms contact,
              QuasiNewtonStrategy strategy = {});

  Stage stage() const override { return m_stage; }
  StepReport step() override;
  const Eigen::VectorXd& positions() const override { return m_solver->positions(); }
  const Eigen::VectorXd& velocities() const override { return m_solver->velocities(); }
  double time() const override { return m_offset + m_solver->time(); }
  bool atRest() const override { return m_solver->atRest(); }
  void setDrag(int vertex, const Eigen::Vector3d& target) override { m_solver->setDrag(vertex, target); }
  void requestCancel() override { m_solver->requestCancel(); }
  void clearCancel() override { m_solver->clearCancel(); }
  std::vector<std::string> terms() const override { return m_solver->energyNames(); }
  Eigen::VectorXi contactMask() const override;
  Eigen::VectorXi triangleDomains() const override;

 private:
  Stage m_stage;
  double m_offset = 0.0;   // scene time at the solver's time 0, s
  ContactTerms m_contact;  // the collider and the contact energies' handles (the energies are the solver's)
  QuasiNewtonStrategy m_strategy;
  std::unique_ptr<newton::NewtonSolver> m_solver;
};

// The preview stage (DESIGN.md 5a): the drape's model solved by L-BFGS, pd-dd's domain-decomposed system of the same
// model as its initial Hessian, at the preview's step. From the placed garment (start.time 0, no velocities) it
// relaxes as the drape does, its first steps a quarter of the preview's.
std::unique_ptr<StageSolver> makePreviewStage(const model::ClothModel& model, const SimulationSettings& settings,
                                              ContactTerms contact, const StageStart& start, bool placed);

// A preview run alone, once it has settled: Newton's steps on the same model, labelled the preview, from start (its
// positions, velocities and time), from the drape's h_max growing up to the preview's step, without relaxation.
std::unique_ptr<StageSolver> makeSettleStage(const model::ClothModel& model, const SimulationSettings& settings,
                                             ContactTerms contact, const StageStart& start);

// The drape stage: Newton. From the placed garment (placed true) with its relaxation; from a preview's state with
// its step starting at h_max and growing up to h_max_factor_after_preview times it, without relaxation unless
// relaxation_after_preview.
std::unique_ptr<StageSolver> makeDrapeStage(const model::ClothModel& model, const SimulationSettings& settings,
                                            ContactTerms contact, const StageStart& start, bool placed);

}  // namespace drape
