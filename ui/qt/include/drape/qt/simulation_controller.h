#pragma once
// The UI-thread side of the simulation: owns the worker thread and the SimulationWorker on it, forwards
// commands through queued calls and re-emits the worker's signals on the UI thread. Destroying the controller
// (closing the window) cancels a running step and joins the thread.
#include <QObject>
#include <QThread>
#include <memory>

#include "drape/qt/simulation_worker.h"

namespace drape::qt {

class SimulationController : public QObject {
  Q_OBJECT

 public:
  explicit SimulationController(QObject* parent = nullptr);
  ~SimulationController() override;

  // Hands a simulation (owned from now on by the worker) over; the previous one is dropped.
  void setSimulation(std::shared_ptr<Simulation> simulation);
  // Hands over the simulation of an edited scene built to continue the current one (Simulation(scene,
  // latestResumeState())); a running simulation keeps running, without interrupting the step in progress.
  void continueWith(std::shared_ptr<Simulation> simulation);
  void start();    // steps the current simulation in its current stage (also continues after pause or cancel)
  void preview();  // the fast preview (SimulationWorker::startPreview)
  void drape();    // the Newton drape, from the preview state when a preview has run (SimulationWorker::startDrape)
  void pause();
  void resume();  // same as start()
  void reset();   // back to the placed garment
  void cancel();  // interrupts the current step; resume(), drape(), reset() or a new simulation continue
  // Grab-drag: pulls garment vertex towards target (metres) from the worker's next step; vertex < 0 releases.
  void setDrag(int vertex, const Eigen::Vector3d& target);

  // Where the worker's simulation is (thread-safe copy after its latest step); nullopt at the placed garment.
  std::optional<ResumeState> latestResumeState() const { return m_worker->latestResumeState(); }
  // "placed", "preview" or "drape" as last reported to the UI thread; empty before any simulation.
  Stage stage() const { return m_stage; }
  RunState runState() const { return m_lastState; }
  // Latest snapshot received on the UI thread (null before the first).
  std::shared_ptr<const Snapshot> latestSnapshot() const { return m_latest; }
  SimulationWorker* worker() const { return m_worker; }

 signals:
  void snapshotReady(std::shared_ptr<const drape::Snapshot> snapshot);
  void stepReported(drape::StepReport report);
  void runStateChanged(drape::qt::RunState state);
  void stageChanged(drape::Stage stage);
  void errorOccurred(QString message);
  void infoOccurred(QString message);
  void qualityReported(drape::QualityReport report);

 private:
  QThread m_thread;
  SimulationWorker* m_worker = nullptr;  // lives on m_thread; deleted after the thread is joined
  RunState m_lastState = RunState::Empty;
  Stage m_stage = Stage::Placed;
  std::shared_ptr<const Snapshot> m_latest;
};

}  // namespace drape::qt
