#pragma once
// The object that owns a drape::Simulation and steps it, living on its own QThread (SimulationController
// moves it there). The UI thread never calls step(): it talks to the worker through queued slots and receives
// snapshots and step reports through queued signals. cancel(), runState(), stage() and latestResumeState()
// are callable from any thread.
#include <QObject>
#include <QString>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>

#include <Eigen/Core>

#include "drape/sim/drape_quality.h"
#include "drape/sim/simulation.h"
#include "drape/sim/snapshot.h"

namespace drape::qt {

// What the worker is doing; reported through SimulationWorker::runStateChanged.
enum class RunState {
  Empty,      // no simulation yet
  Ready,      // a simulation at its start (placed garment), not running
  Running,    // stepping
  Paused,     // stopped by pause(), after a diverged step, or a continued edit while stopped; resume() continues
  Finished,   // at rest or at the scene's time/step limit
  Cancelled,  // interrupted by cancel(); resume(), drape() or reset() continue
};
const char* toString(RunState state);

class SimulationWorker : public QObject {
  Q_OBJECT

 public:
  explicit SimulationWorker(QObject* parent = nullptr);
  ~SimulationWorker() override;

  // Thread-safe: interrupts the step in progress (Simulation::requestCancel) and stops stepping. The state turns
  // Cancelled on the worker thread, after the report of a step in progress (Cancelled or not) has been sent. A
  // later start/preview/drape command clears the engine's cancel flag and continues from the kept state.
  void cancel();
  // Thread-safe: the interruption of cancel() without its Cancelled state and snapshot, for a command queued right
  // after it that replaces the simulation and announces the next state itself (reset).
  void interrupt();
  // Thread-safe: the number of cancel() and interrupt() calls so far. A run command carries the value its caller saw, so a
  // command issued before a cancel (still queued when the cancel happens) does not undo it.
  int cancelGeneration() const { return m_cancelGeneration.load(); }
  // Thread-safe: the latest state.
  RunState runState() const { return m_state.load(); }
  // Thread-safe: "placed" (no step yet), "preview" (L-BFGS on the drape's model) or "drape" (Newton); empty without a simulation.
  Stage stage() const;  // Placed before a simulation is set
  // Thread-safe: where the simulation is after its latest step (copied after every step), for an edited scene
  // to continue from; nullopt while the simulation is at the placed garment.
  std::optional<ResumeState> latestResumeState() const;
  // Smallest wall-clock interval between two snapshots while running (the last one is always sent), ms.
  void setSnapshotInterval(int milliseconds) { m_snapshotIntervalMs.store(milliseconds); }

 public slots:
  // Takes the simulation (built and validated on the UI thread) and sends its first snapshot.
  void setSimulation(std::shared_ptr<drape::Simulation> simulation);
  // Takes the simulation of an edited scene that continues the current one (built with its ResumeState): keeps
  // running when running, else stops in Paused; a grabbed vertex stays grabbed.
  void continueWith(std::shared_ptr<drape::Simulation> simulation);
  // Steps the current simulation, whatever its stage, until paused, finished, cancelled or diverged (each step
  // is a separate event, so the other slots run between steps). Ignored when a cancel came after the caller
  // read cancelGeneration (pass -1 to skip that check).
  void start(int generation = -1);
  // The fast preview (solver.stage preview): from the placed garment, or continuing a preview.
  // Ignored once the Newton drape has started (Reset first).
  void startPreview(int generation = -1);
  // The accurate Newton drape (solver.stage drape): from the current preview state when a preview has run
  // (velocities reset), else from the placed garment; continues a drape that was paused or cancelled.
  void startDrape(int generation = -1);
  void pause();
  // Rebuilds the simulation from its scene (back to the placed garment) and sends that snapshot.
  void reset();
  // Pulls garment vertex towards target (metres) by a spring from the next step on; vertex < 0 releases it.
  // Kept across continued edits.
  void setDrag(int vertex, Eigen::Vector3d target);

 signals:
  void snapshotReady(std::shared_ptr<const drape::Snapshot> snapshot);
  void stepReported(drape::StepReport report);
  void runStateChanged(drape::qt::RunState state);
  void stageChanged(drape::Stage stage);
  // A diverged step or a failed rebuild: shown to the user; the last good state is kept.
  void errorOccurred(QString message);
  // Something that happened and needs no answer: a stage at rest, the drape taking over from the preview.
  void infoOccurred(QString message);
  // The quality verdict (sim/drape_quality.h) of a stage that finished (at rest or at the scene's time or step
  // limit), computed on the worker thread before the Finished state is announced.
  void qualityReported(drape::QualityReport report);

 private slots:
  void stepOnce();
  // Worker thread: shows a pending cancel (state Cancelled and a snapshot) once no step is running.
  void finishCancel();

 private:
  std::shared_ptr<Simulation> current() const;
  // Installs simulation as current (announcing its stage) without changing the run state.
  void replace(std::shared_ptr<Simulation> simulation);
  // Rebuilds the current simulation's scene with solver.stage = stage, continuing from `from` when given.
  bool rebuild(const std::string& stage, const ResumeState* from);
  void setState(RunState state);
  void updateStage();
  void publishResumeState();
  void sendSnapshot();
  void scheduleStep();
  bool cancelledSince(int generation) const { return generation >= 0 && generation != m_cancelGeneration.load(); }

  mutable std::mutex m_mutex;  // guards m_simulation (the pointer, not the object), m_stage and m_resume
  std::shared_ptr<Simulation> m_simulation;
  std::optional<Stage> m_stage;  // none until the first simulation announces its stage
  std::optional<ResumeState> m_resume;
  std::atomic<RunState> m_state{RunState::Empty};
  std::atomic<bool> m_running{false};
  std::atomic<bool> m_cancelPending{false};  // cancel() called, finishCancel not yet run
  std::atomic<int> m_snapshotIntervalMs{33};
  std::atomic<int> m_cancelGeneration{0};
  std::chrono::steady_clock::time_point m_lastSnapshot;
  bool m_stepQueued = false;  // a stepOnce event is pending (worker thread only)
  int m_dragVertex = -1;      // worker thread only
  Eigen::Vector3d m_dragTarget = Eigen::Vector3d::Zero();
};

}  // namespace drape::qt
