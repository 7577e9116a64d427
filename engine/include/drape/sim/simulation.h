#pragma once
// The one step API for the GUI and the CLI (STYLE.md): a Simulation owns a scene's garment and holds one stage solver
// at a time (DESIGN.md 5b), advances one step at a time, and hands out owned snapshots. Nothing here knows whether a
// window exists. Stages follow solver.stage: "preview" (the drape's model by L-BFGS, pd-dd's system as its initial
// Hessian), "drape" (Newton from the placed garment) or "full" (the preview until it settles or
// solver.preview.max_time, then the Newton drape from the preview's positions, velocities and time).
#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "drape/garment/garment.h"
#include "drape/garment/garment_builder.h"
#include "drape/scene/scene.h"
#include "drape/scene/stage_settings.h"
#include "drape/sim/scene_garment.h"
#include "drape/sim/snapshot.h"
#include "drape/sim/stage.h"

namespace drape {

namespace collision {
class AvatarCollider;
}

enum class StepStatus { Converged, MaxIterations, Diverged, Cancelled };
const char* toString(StepStatus status);

struct StepReport {
  StepStatus status = StepStatus::Converged;
  Stage stage = Stage::Preview;   // Preview or Drape
  double time = 0.0;              // simulated seconds after the step
  double h = 0.0;                 // step taken, s
  int iterations = 0;             // Newton iterations (drape) or L-BFGS iterations (preview)
  int cgIterations = 0;           // PCG iterations of the drape's Newton systems
  int lineSearchEvaluations = 0;  // preview: potential evaluations of its line searches
  bool quasiNewton = false;       // the step was solved by L-BFGS (the preview)
  int domains = 0;                // preview: METIS domains of its initial Hessian
  int splits = 0;                 // time-split retries
  double residual = 0.0;
  double kineticEnergy = 0.0;  // 99th percentile of per-vertex kinetic energy, J
  int contacts = 0;            // garment vertices in contact with a collider
  int featureContacts = 0;     // avatar feature points pressing on a garment triangle (contact.avatar_features)
  double maxStrain = 0.0;      // largest triangle stretch (0.05 = 5%)
  int maxStrainTriangle = -1;  // the triangle stretched most (garment triangle index); -1: no triangles
  double wallTime = 0.0;       // seconds spent in this step
  // Wall seconds of this step in Hessian assembly, gradient (residual) evaluations, linear solves.
  double assemblyTime = 0.0;
  double gradientTime = 0.0;
  double linearSolveTime = 0.0;
  double contactQueryTime = 0.0;  // wall seconds in the contact terms' per-step queries (candidates, friction's set)
  // Equilibrium at the step's end (newton::NewtonStepReport): the largest and the RMS unbalanced force per vertex as a
  // fraction of its weight, and the step's largest vertex displacement, m.
  double forceMax = 0.0;
  double forceRms = 0.0;
  double displacementMax = 0.0;
  bool hessianReused = false;    // drape: the first Newton iteration solved with an earlier step's elastic Hessian
  int coarseSolves = 0;          // drape: linear solves with the two-level PCG (solver.cg.coarse_aggregate)
  int coarseFactorizations = 0;  // drape: coarse matrices factorised for them (solver.cg.coarse_lagged)
  int coupledSolves = 0;         // drape: linear solves with coupled groups (solver.cg.coupled_groups)
  bool relaxing = false;         // the step was inside the initial relaxation (velocities zeroed)
  bool atRest = false;           // early stop reached
};

// Where a simulation's wall time went, summed over its steps (s): assembling Hessians (the preview: its
// preconditioner), solving the linear systems (the preview: its search directions), the contact terms' per-step
// queries, evaluating residuals for the line searches (the preview: all its gradient and potential evaluations), and
// the rest of each step (the stage's statistics, the strain and explosion checks, the hand-over).
struct PhaseProfile {
  double assembly = 0.0;
  double linearSolve = 0.0;
  double contactQueries = 0.0;
  double lineSearch = 0.0;
  double bookkeeping = 0.0;
  double total() const { return assembly + linearSolve + contactQueries + lineSearch + bookkeeping; }
  void add(const StepReport& r);
};

// Where a running simulation is, so that the simulation of an edited scene (another fabric, a pin added in the
// GUI) can continue from it instead of from the placed garment.
struct ResumeState {
  Stage stage = Stage::Preview;       // Preview or Drape when captured
  int vertexCount = 0;                // garment vertices; a garment meshed differently cannot resume
  Eigen::MatrixX3d positions;         // |V| x 3, metres
  Eigen::MatrixX3d velocities;        // |V| x 3, m/s
  double time = 0.0;                  // scene time, s
  Eigen::MatrixX3d previewPositions;  // the state the preview handed to the drape; no rows when the drape
                                      // started from the placed garment
  double previewTime = 0.0;           // scene time of previewPositions, s
  // The mesh the state is on, for an edited pattern: when set and the new scene meshes the pattern differently, the
  // state is carried to the new mesh through the pattern coordinates (garmentTransfer). Not set: a mesh with another
  // vertex count starts over.
  std::shared_ptr<const Garment> garment;
};

// The state the scene's stage starts from at given vertex positions (|V| x 3, metres; drape --from): stages
// preview and full run the preview from them at rest, at time 0, without relaxation; stage drape runs the drape from
// them as from a preview's hand-over (velocities zero, no relaxation unless solver.newton.relaxation_after_preview,
// h_max times solver.newton.h_max_factor_after_preview).
ResumeState startStateAt(StagePlan plan, const Eigen::MatrixX3d& positions);

class StageSolver;

class Simulation {
 public:
  // Builds the garment, pins and the stage the scene starts with; throws InputError for bad scenes.
  explicit Simulation(Scene scene);
  // The same for an edited scene, continuing from `from` when the garment has the same vertex count or `from`
  // carries its garment (ResumeState::garment): a preview continues from its current positions, velocities and time
  // (when the scene's stage runs a preview); a drape restarts from the last preview state (previewPositions), else
  // from the placed garment. resumed() tells whether the state was used.
  Simulation(Scene scene, const ResumeState& from);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  // Advances one step; never touches UI, never throws for numerical trouble (a Diverged step keeps the last
  // good state). A step that leaves the garment exploded (sim/exploded_state.h: a triangle stretched past any
  // fabric, a vertex far outside the scene) is Diverged too, in every stage: positions() stay the state before it,
  // divergedReason() says where, and every later step is Diverged at once.
  StepReport step();
  // Why the garment exploded, naming the triangle or vertex; empty unless a step ended Diverged that way.
  const std::string& divergedReason() const { return m_divergedReason; }
  // True when the garment is at rest (early stop) or the scene's time/step limit is reached.
  bool finished() const;
  // Why the run finished: "AtRest", "MaxSimTime" (solver.max_sim_time of scene time; for a drape built from a
  // ResumeState's preview state, of the drape's own time) or "MaxSteps" (solver.max_steps); empty
  // while it is not finished. A Diverged or Cancelled step is the step's own status (StepReport).
  std::string endReason() const;
  Snapshot snapshot() const;
  void requestCancel();
  // Forgets a cancel request (after a cancelled step, so that the next step runs).
  void clearCancel();

  // A grabbed garment vertex pulled towards target (metres) by a spring, from the next step on; vertex < 0
  // releases it. Survives the switch from the preview to the drape. Throws std::invalid_argument when out of range.
  void setDrag(int vertex, const Eigen::Vector3d& target);
  int draggedVertex() const { return m_dragVertex; }

  ResumeState resumeState() const;
  bool resumed() const { return m_resumed; }

  const Scene& scene() const { return m_scene; }
  // The scene's settings as the stages read them.
  const SimulationSettings& settings() const { return m_settings; }
  const Garment& garment() const { return m_garment; }
  const std::vector<int>& pinned() const { return m_pinned; }
  // Names of the terms the current stage solves ("membrane", "bending", "avatar_contact", ...).
  std::vector<std::string> terms() const;
  Stage stage() const;                 // Preview or Drape
  Eigen::MatrixX3d positions() const;  // |V| x 3, metres
  double time() const;
  int steps() const { return m_steps; }
  // The last step's report (a default one before the first step).
  const StepReport& lastStep() const { return m_lastStep; }
  // The wall time of the steps so far, by phase.
  const PhaseProfile& profile() const { return m_profile; }
  // Contact thickness the solvers use, metres (contact.thickness, else the thickest fabric, at least 2 mm).
  double contactThickness() const { return m_settings.contact.thickness; }
  // The avatar and generated colliders, merged, as the stages' contact sees them; nullptr when the scene has none.
  const collision::AvatarCollider* collider() const;

 private:
  struct Model;
  Scene m_scene;
  SimulationSettings m_settings;
  Garment m_garment;
  std::vector<int> m_pinned;
  TriangleMesh m_colliderMesh;  // avatar and generated colliders, merged
  std::unique_ptr<Model> m_model;
  std::unique_ptr<StageSolver> m_stage;
  int m_steps = 0;
  PhaseProfile m_profile;
  StepReport m_lastStep;
  bool m_atRest = false;
  bool m_resumed = false;
  double m_stageStart = 0.0;       // scene time at which the current stage started, s
  double m_settledSince = -1.0;    // the preview: scene time since which it has moved slower than
                                   // solver.preview.handoff_speed (-1: it has not)
  bool m_settling = false;         // a preview run alone settles by Newton's steps (startSettling)
  Eigen::MatrixX3d m_handOver;     // the state the preview handed to the drape; no rows: the drape started placed
  double m_handOverTime = 0.0;     // scene time of m_handOver, s
  bool m_drapeOwnBudget = false;   // the drape started from a resumed preview state (endReason)
  Eigen::AlignedBox3d m_sceneBox;  // the colliders and the garment as placed (or resumed): explodedReason
  Eigen::MatrixX3d m_lastGood;     // positions before the step that exploded (divergedReason)
  std::string m_divergedReason;
  int m_dragVertex = -1;
  Eigen::Vector3d m_dragTarget = Eigen::Vector3d::Zero();

  void build(const ResumeState* from);
  // Starts the preview from `from`'s positions, velocities and time (nullptr: the placed garment, relaxing).
  void startPreview(const ResumeState* from);
  // Starts the Newton drape from positions and velocities (|V| x 3; no rows: the placed garment, relaxing) at scene
  // time `time`.
  void startDrape(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3d& velocities, double time);
  // The preview has settled: the speeds of its steps' motion (positions before the step: 3|V|) have stayed below
  // solver.preview.handoff_speed for 0.1 s, outside its relaxation and while nothing is dragged. The full pipeline
  // then hands over to the drape; a preview run alone settles by Newton's steps (startSettling).
  bool previewSettled(const StepReport& report, const Eigen::VectorXd& before);
  // A preview run alone, settled: Newton's steps at the preview's step take it to rest by the drape's own test, which
  // L-BFGS's few iterations a step cannot pass (their errors keep the garment creeping). A drag goes back to L-BFGS.
  void startSettling();
};

// The simulation of scene's stage started at the positions of a garment state file (drape --from, the GUI's Load
// Garment State; io/garment_state.h): the file is read before the garment is meshed, then checked against it.
// Throws InputError naming the file when it cannot be read or belongs to another garment.
std::unique_ptr<Simulation> simulationFromStateFile(Scene scene, const std::filesystem::path& file);

}  // namespace drape
