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
  void start();  // Drape: starts stepping (also continues after a pause)
  void pause();
  void resume();  // same as start()
  void reset();   // back to the placed garment
  void cancel();  // interrupts the current step; reset() or a new simulation continues

  RunState runState() const { return m_lastState; }
  // Latest snapshot received on the UI thread (null before the first).
  std::shared_ptr<const Snapshot> latestSnapshot() const { return m_latest; }
  SimulationWorker* worker() const { return m_worker; }

 signals:
  void snapshotReady(std::shared_ptr<const drape::Snapshot> snapshot);
  void stepReported(drape::StepReport report);
  void runStateChanged(drape::qt::RunState state);
  void errorOccurred(QString message);

 private:
  QThread m_thread;
  SimulationWorker* m_worker = nullptr;  // lives on m_thread; deleted after the thread is joined
  RunState m_lastState = RunState::Empty;
  std::shared_ptr<const Snapshot> m_latest;
};

}  // namespace drape::qt
