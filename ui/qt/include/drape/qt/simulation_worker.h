#pragma once
// The object that owns a drape::Simulation and steps it, living on its own QThread (SimulationController
// moves it there). The UI thread never calls step(): it talks to the worker through queued slots and receives
// snapshots and step reports through queued signals. cancel() is the one function callable from any thread.
#include <QObject>
#include <QString>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>

#include "drape/sim/simulation.h"
#include "drape/sim/snapshot.h"

namespace drape::qt {

// What the worker is doing; reported through SimulationWorker::runStateChanged.
enum class RunState {
  Empty,      // no simulation yet
  Ready,      // a simulation at its start (placed garment), not running
  Running,    // stepping
  Paused,     // stopped by pause() or after a diverged step; resume() continues
  Finished,   // at rest or at the scene's time/step limit
  Cancelled,  // interrupted by cancel(); reset() starts again
};
const char* toString(RunState state);

class SimulationWorker : public QObject {
  Q_OBJECT

 public:
  explicit SimulationWorker(QObject* parent = nullptr);
  ~SimulationWorker() override;

  // Thread-safe: interrupts the step in progress (Simulation::requestCancel) and stops stepping. The engine's
  // cancel flag is sticky, so the simulation then stays stopped until reset() or a new simulation.
  void cancel();
  // Thread-safe: the latest state.
  RunState runState() const { return m_state.load(); }
  // Smallest wall-clock interval between two snapshots while running (the last one is always sent), ms.
  void setSnapshotInterval(int milliseconds) { m_snapshotIntervalMs.store(milliseconds); }

 public slots:
  // Takes the simulation (built and validated on the UI thread) and sends its first snapshot.
  void setSimulation(std::shared_ptr<drape::Simulation> simulation);
  // Steps until paused, finished, cancelled or diverged (each step is a separate event, so the other
  // slots run between steps).
  void start();
  void pause();
  // Rebuilds the simulation from its scene (back to the placed garment) and sends that snapshot.
  void reset();

 signals:
  void snapshotReady(std::shared_ptr<const drape::Snapshot> snapshot);
  void stepReported(drape::StepReport report);
  void runStateChanged(drape::qt::RunState state);
  // A diverged step or a failed rebuild: shown to the user; the last good state is kept.
  void errorOccurred(QString message);

 private slots:
  void stepOnce();

 private:
  std::shared_ptr<Simulation> current() const;
  void setState(RunState state);
  void sendSnapshot();
  void scheduleStep();

  mutable std::mutex m_mutex;  // guards m_simulation (the pointer, not the object)
  std::shared_ptr<Simulation> m_simulation;
  std::atomic<RunState> m_state{RunState::Empty};
  std::atomic<bool> m_running{false};
  std::atomic<int> m_snapshotIntervalMs{33};
  std::chrono::steady_clock::time_point m_lastSnapshot;
  bool m_stepQueued = false;  // a stepOnce event is pending (worker thread only)
};

}  // namespace drape::qt
