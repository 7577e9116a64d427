#pragma once
// The one step API for the GUI and the CLI (STYLE.md): a Simulation owns a scene's garment and solvers, advances
// one step at a time, and hands out owned snapshots. Nothing here knows whether a window exists.
// Stages follow solver.stage: "preview" (PD-DD only), "drape" (Newton from the placed garment) or "full"
// (the preview until it settles or solver.preview.max_time, then the Newton drape from the preview's
// positions with velocities reset).
#include <Eigen/Geometry>
#include <atomic>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "drape/garment/garment.h"
#include "drape/garment/garment_builder.h"
#include "drape/pd/preview_settings.h"
#include "drape/scene/scene.h"
#include "drape/sim/scene_garment.h"
#include "drape/sim/snapshot.h"
#include "drape/sim/stage.h"

namespace drape {

namespace collision {
class AvatarCollider;
}

enum class StepStatus { Converged, MaxIterations, Diverged, Cancelled };
const char* toString(StepStatus status);

// The Courant number the scene's preview softens its fabric to (preview_fabric.h; 0: not softened):
// solver.preview.courant_limit, or in the full pipeline the softer of it and solver.preview.pipeline_courant_limit.
double previewCourantLimitOf(const Scene& scene);

struct StepReport {
  StepStatus status = StepStatus::Converged;
  Stage stage = Stage::Preview;  // Preview or Drape
  double time = 0.0;           // simulated seconds after the step
  double h = 0.0;              // step taken, s
  int iterations = 0;          // Newton iterations (drape) or local-global iterations (preview)
  int cgIterations = 0;        // PCG iterations (drape: Newton systems; preview: collision-aware solve)
  int domains = 0;             // preview: METIS domains used
  bool sewn = false;           // preview: the garment counts as sewn (solver.preview.sewn_gap)
  bool assembly = false;       // preview: the step sewed the coarser mesh of solver.preview.assembly_edge_length
  double collisionTime = 0.0;  // preview phase times, seconds
  double localTime = 0.0;
  double globalTime = 0.0;
  int splits = 0;              // time-split retries
  double residual = 0.0;
  double kineticEnergy = 0.0;  // 99th percentile of per-vertex kinetic energy, J
  int contacts = 0;            // garment vertices in contact with a collider
  int featureContacts = 0;     // drape: avatar feature points pressing on a garment triangle (contact.avatar_features)
  double maxStrain = 0.0;      // largest triangle stretch (0.05 = 5%)
  int maxStrainTriangle = -1;  // the triangle stretched most (garment triangle index); -1: no triangles
  double wallTime = 0.0;       // seconds spent in this step
  // Drape stage: wall seconds of this step in Hessian assembly, gradient (residual) evaluations, linear solves.
  double assemblyTime = 0.0;
  double gradientTime = 0.0;
  double linearSolveTime = 0.0;
  bool hessianReused = false;  // drape: the first Newton iteration solved with an earlier step's elastic Hessian
  int coarseSolves = 0;        // drape: linear solves with the two-level PCG (solver.cg.coarse_aggregate)
  int coarseFactorizations = 0;  // drape: coarse matrices factorised for them (solver.cg.coarse_lagged)
  int coupledSolves = 0;       // drape: linear solves with coupled groups (solver.cg.coupled_groups)
  bool atRest = false;         // early stop reached
  // preview, solver.preview.method quasi_newton: the step solved the drape's model by L-BFGS (iterations counts its
  // iterations, lineSearchEvaluations the potential evaluations of its line searches; cgIterations stays 0).
  bool quasiNewton = false;
  int lineSearchEvaluations = 0;
};

// Where a running simulation is, so that the simulation of an edited scene (another fabric, a pin added in the
// GUI) can continue from it instead of from the placed garment.
struct ResumeState {
  Stage stage = Stage::Preview;      // Preview or Drape when captured
  bool assembling = false;           // captured while the preview sewed its coarser assembly mesh (not resumed)
  int vertexCount = 0;               // garment vertices; a garment meshed differently cannot resume
  Eigen::MatrixX3d positions;        // |V| x 3, metres
  Eigen::MatrixX3d velocities;       // |V| x 3, m/s
  double time = 0.0;                 // scene time, s
  Eigen::MatrixX3d previewPositions;  // the state the preview handed to the drape; no rows when the drape
                                      // started from the placed garment
  double previewTime = 0.0;          // scene time of previewPositions, s
  double previewCourantLimit = 0.0;  // the Courant number the preview's fabric was softened to (0: not softened)
  bool previewTargetsFreed = false;  // the preview started over with contact targets not held before it was sewn
};

// The state the scene's stage starts from at given vertex positions (|V| x 3, metres; drape --from): stages
// preview and full run the preview from them at rest, at time 0 (its quasi-static start included); stage drape
// runs the drape from them as from a preview's hand-over (velocities zero, no relaxation unless
// solver.newton.relaxation_after_preview, h_max times solver.newton.h_max_factor_after_preview).
ResumeState startStateAt(StagePlan plan, const Eigen::MatrixX3d& positions);

class Simulation {
 public:
  // Builds the garment, pins and the solver terms the scene needs; throws InputError for bad scenes.
  explicit Simulation(Scene scene);
  // The same for an edited scene, continuing from `from` when the garment has the same vertex count: a preview
  // continues from its current positions, velocities and time (when the scene's stage runs a preview); a drape
  // restarts from the last preview state (previewPositions), else from the placed garment. resumed() tells
  // whether the state was used.
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
  const Garment& garment() const { return m_garment; }
  const std::vector<int>& pinned() const { return m_pinned; }
  // Names of the terms the current stage's solver uses ("membrane", "bending", "avatar_contact", ...).
  std::vector<std::string> terms() const;
  Stage stage() const;  // Preview or Drape
  // The preview is sewing the garment on its coarser assembly mesh (solver.preview.assembly_edge_length); the
  // garment's positions are carried over from it.
  bool assembling() const;
  Eigen::MatrixX3d positions() const;  // |V| x 3, metres
  double time() const;
  int steps() const { return m_steps; }
  // A tear (solver.preview.failure_strain) with a fabric stiffer than solver.preview.retry_courant_limit first starts
  // the preview over from the placed garment at scene time 0, its fabric softened to that Courant number
  // (solver.preview.courant_limit). A tear with no such retry left starts the preview over in the same way once with
  // its avatar contact targets never held before the garment is sewn (solver.preview.retry_without_held_targets;
  // previewTargetsFreed()), and so does a full pipeline's preview about to hand over a triangle stretched past
  // solver.preview.handoff_strain. Only a tear after that is given up (previewFailure()).
  //
  // The final verdict on the preview: why it was given up and the drape started from the placed garment instead, at
  // scene time 0 (in the full pipeline, or when a drape was to start from a torn preview state,
  // ResumeState::previewPositions); or, for a preview run alone (solver.stage preview), which is not given up, from
  // its first torn step with no restart left on, that its result is wrong and only the drape's can be trusted. Empty
  // while none of this happened: a tear that started the preview over is not a failure (previewRestartReasons()).
  const std::string& previewFailure() const { return m_previewFailure; }
  // What each start-over said, in order: how far the tear stretched, when and where, and how the preview starts over
  // ("...; the preview starts over from the placed garment with ..."). One entry per restart.
  const std::vector<std::string>& previewRestartReasons() const { return m_previewRestartReasons; }
  int previewRestarts() const { return static_cast<int>(m_previewRestartReasons.size()); }
  // The start-overs the preview recovered from: previewRestartReasons() while the preview has not been given up
  // after them (previewFailure() empty), else none.
  std::vector<std::string> previewRecoveries() const {
    return m_previewFailure.empty() ? m_previewRestartReasons : std::vector<std::string>();
  }
  // The Courant number the preview's fabric is softened to: previewCourantLimitOf(scene()), or the retry's after a
  // restart; 0: the fabric's own stiffness.
  double previewCourantLimit() const { return m_courantLimit; }
  // The preview started over with solver.preview.hold_targets_step 0 after a tear.
  bool previewTargetsFreed() const { return m_targetsFreed; }
  // The fabric's own Courant number at the preview's time step (pd::courantNumber).
  double previewCourantNumber() const { return m_courantNumber; }
  // Contact thickness the solvers use, metres (contact.thickness, else the thickest fabric, at least 2 mm).
  double contactThickness() const;
  // The avatar and generated colliders, merged, as both solvers' contact sees them; nullptr when the scene has none.
  const collision::AvatarCollider* collider() const;

 private:
  struct Solver;
  Scene m_scene;
  Garment m_garment;
  std::vector<int> m_pinned;
  TriangleMesh m_colliderMesh;  // avatar and generated colliders, merged
  std::unique_ptr<Solver> m_solver;
  int m_steps = 0;
  bool m_atRest = false;
  bool m_resumed = false;
  double m_restSince = -1.0;  // preview: time the settle criterion started to hold
  std::string m_previewFailure;
  bool m_previewWrong = false;  // preview alone: a tear after which it went on has been said
  std::vector<std::string> m_previewRestartReasons;
  double m_courantLimit = 0.0;     // previewCourantLimit()
  bool m_targetsFreed = false;     // previewTargetsFreed()
  double m_courantNumber = 0.0;    // previewCourantNumber()
  double m_overshootSince = -1.0;  // preview: scene time since which the stretch has been extreme (-1: it is not)
  bool m_drapeOwnBudget = false;   // the drape started from a resumed preview state (endReason)
  Eigen::AlignedBox3d m_sceneBox;  // the colliders and the garment as placed (or resumed): explodedReason
  Eigen::MatrixX3d m_lastGood;     // positions before the step that exploded (divergedReason)
  std::string m_divergedReason;
  int m_dragVertex = -1;
  Eigen::Vector3d m_dragTarget = Eigen::Vector3d::Zero();

  // What follows a torn preview (tearReason).
  enum class TearOutcome { DrapeFromPlaced, PreviewGoesOn, PreviewStartsOver, PreviewStartsOverUnheld };

  void build(const ResumeState* from);
  // The scene's preview settings with the fabric softened to previewCourantLimit(), and without held contact targets
  // before the garment is sewn after previewTargetsFreed().
  pd::PreviewSettings previewSettings() const;
  // Starts the preview (over) from the placed garment at scene time 0: on the assembly mesh when startAssembly()
  // does, else on the garment's own.
  void startPreview();
  // The Courant limit a torn preview starts over with: solver.preview.retry_courant_limit when it is on, the
  // preview is not that soft yet and the fabric is stiffer than it; else 0.
  double retryCourantLimit() const;
  // A torn preview with no softer retry left starts over with its contact targets free before it is sewn:
  // solver.preview.retry_without_held_targets is on, it has not done so yet, and the preview holds targets before
  // it is sewn (hold_targets_step above 0, hold_contact_targets off).
  bool retriesUnheld() const;
  // " (triangle t of panel p, at x .., y .., z .. m)": report's most stretched triangle, its centre in x.
  std::string stretchedTriangle(const StepReport& report, const Eigen::MatrixX3d& x) const;
  // Why a step that handed over to the drape a triangle stretched past solver.preview.handoff_strain starts the
  // preview over with its contact targets free, when retriesUnheld(); else empty (held targets can lock a seam
  // stretched, and a drape from such a hand-over takes longer than Newton's alone; docs/ENGINE.md, "Design notes").
  std::string overstretchedHandOverReason(const StepReport& report, const Eigen::MatrixX3d& x) const;
  // The longest preview stage: solver.preview.max_time, or in the full pipeline softened_max_time when that is
  // shorter and the preview's fabric is softened (previewCourantLimit() below the fabric's Courant number).
  double previewMaxTime() const;
  // Starts the preview on the coarser assembly mesh when solver.preview.assembly_edge_length asks for one; false
  // when the scene's own mesh is not that much finer, has no seam, has vertex pins or the pattern does not mesh so
  // coarsely.
  bool startAssembly();
  // Carries the assembly's state over to the garment's own mesh: the preview continues there, or, in the full
  // pipeline once solver.preview.max_time is reached, the drape starts.
  void finishAssembly();
  // The assembly mesh vertex that carries most of garment vertex `vertex` (-1 for -1).
  int assemblyVertex(int vertex) const;
  // A preview step after the quasi-static start (solver.preview.relaxation_time) that left a triangle stretched past
  // solver.preview.failure_strain has torn the garment on the body (the preview's vertex contact lets the body
  // through between vertices). Full pipeline: its state is no start for the drape, which starts from the placed
  // garment instead. Preview alone: the preview goes on, and previewFailure() says, from the first such step on,
  // that its result is not to be trusted. During the quasi-static start a stretch that stays past 4x
  // failure_strain for 3 ms is a tear too (stuckOvershoot).
  void failPreviewIfTorn(const StepReport& report, const Eigen::MatrixX3d& x);  // x: the positions after it
  // Whether the preview's stretch has stayed extreme (see failPreviewIfTorn) up to this step.
  bool stuckOvershoot(const StepReport& report);
  // Why the preview state x (|V| x 3) after `report` is torn (its largest stretch past
  // solver.preview.failure_strain): how far, when, and where (the triangle, its panel and its centre in x), ending
  // with what follows; empty when it is not torn.
  std::string tearReason(const StepReport& report, const Eigen::MatrixX3d& x,
                         TearOutcome then = TearOutcome::DrapeFromPlaced) const;
  // Starts the Newton drape from positions (|V| x 3; no rows = the placed garment) at scene time `time`.
  void startDrape(const Eigen::MatrixX3d& positions, double time);
  // solver.preview.method quasi_newton (simulation_qn_preview.cpp): the Newton drape's own model solved by L-BFGS,
  // from the placed garment (no `from`) or from a state at rest or a preview's resume state (positions, velocities,
  // scene time; no relaxation).
  void startQuasiNewtonPreview(const ResumeState* from);
  // Its step, and the hand-over that switches the same solver to Newton (positions, velocities and time go on).
  StepReport stepQuasiNewtonPreview();
  void handOverToDrape();
  bool quasiNewtonMethod() const;
  // The preview's settle test on the speeds of a step's motion (|V|, m/s): their 99th percentile below
  // solver.preview.rest_speed (preview alone) or handoff_speed for 0.1 s; waiting (assembling, relaxing): not yet.
  bool previewSettled(std::vector<double> speeds, bool waiting);
};

// The simulation of scene's stage started at the positions of a garment state file (drape --from, the GUI's Load
// Garment State; io/garment_state.h): the file is read before the garment is meshed, then checked against it.
// Throws InputError naming the file when it cannot be read, belongs to another garment, or the stage cannot start
// from it (a drape from a state stretched past solver.preview.failure_strain).
std::unique_ptr<Simulation> simulationFromStateFile(Scene scene, const std::filesystem::path& file);

}  // namespace drape
