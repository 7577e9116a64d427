#include "drape/qt/simulation_controller.h"

#include <QMetaObject>

namespace drape::qt {

SimulationController::SimulationController(QObject* parent) : QObject(parent) {
  qRegisterMetaType<std::shared_ptr<const Snapshot>>();
  qRegisterMetaType<std::shared_ptr<Simulation>>();
  qRegisterMetaType<StepReport>();
  qRegisterMetaType<RunState>();
  qRegisterMetaType<Stage>();
  qRegisterMetaType<QualityReport>();
  m_thread.setObjectName("drape-simulation");
  m_worker = new SimulationWorker;
  m_worker->moveToThread(&m_thread);
  connect(
      m_worker, &SimulationWorker::snapshotReady, this,
      [this](std::shared_ptr<const Snapshot> snapshot) {
        m_latest = snapshot;
        emit snapshotReady(std::move(snapshot));
      },
      Qt::QueuedConnection);
  connect(m_worker, &SimulationWorker::stepReported, this, &SimulationController::stepReported, Qt::QueuedConnection);
  connect(
      m_worker, &SimulationWorker::runStateChanged, this,
      [this](RunState state) {
        m_lastState = state;
        emit runStateChanged(state);
      },
      Qt::QueuedConnection);
  connect(
      m_worker, &SimulationWorker::stageChanged, this,
      [this](Stage stage) {
        m_stage = stage;
        emit stageChanged(stage);
      },
      Qt::QueuedConnection);
  connect(m_worker, &SimulationWorker::errorOccurred, this, &SimulationController::errorOccurred, Qt::QueuedConnection);
  connect(m_worker, &SimulationWorker::infoOccurred, this, &SimulationController::infoOccurred, Qt::QueuedConnection);
  connect(m_worker, &SimulationWorker::qualityReported, this, &SimulationController::qualityReported,
          Qt::QueuedConnection);
  m_thread.start();
}

SimulationController::~SimulationController() {
  // Safe during a step: the step returns Cancelled at its next iteration, the event loop then quits.
  m_worker->cancel();
  m_thread.quit();
  m_thread.wait();
  delete m_worker;
}

void SimulationController::setSimulation(std::shared_ptr<Simulation> simulation) {
  // A running step of the old simulation is interrupted so the new one takes over promptly.
  m_worker->cancel();
  QMetaObject::invokeMethod(m_worker, "setSimulation", Qt::QueuedConnection,
                            Q_ARG(std::shared_ptr<drape::Simulation>, std::move(simulation)));
}

void SimulationController::continueWith(std::shared_ptr<Simulation> simulation) {
  QMetaObject::invokeMethod(
      m_worker, [worker = m_worker, simulation = std::move(simulation)] { worker->continueWith(simulation); },
      Qt::QueuedConnection);
}

// Run commands carry the cancel generation seen now: a cancel issued after them wins.
void SimulationController::start() {
  QMetaObject::invokeMethod(
      m_worker, [worker = m_worker, g = m_worker->cancelGeneration()] { worker->start(g); }, Qt::QueuedConnection);
}

void SimulationController::preview() {
  QMetaObject::invokeMethod(
      m_worker, [worker = m_worker, g = m_worker->cancelGeneration()] { worker->startPreview(g); },
      Qt::QueuedConnection);
}

void SimulationController::drape() {
  QMetaObject::invokeMethod(
      m_worker, [worker = m_worker, g = m_worker->cancelGeneration()] { worker->startDrape(g); },
      Qt::QueuedConnection);
}

void SimulationController::setDrag(int vertex, const Eigen::Vector3d& target) {
  QMetaObject::invokeMethod(
      m_worker, [worker = m_worker, vertex, target] { worker->setDrag(vertex, target); }, Qt::QueuedConnection);
}

void SimulationController::pause() {
  QMetaObject::invokeMethod(m_worker, &SimulationWorker::pause, Qt::QueuedConnection);
}

void SimulationController::resume() {
  start();
}

void SimulationController::reset() {
  // Interrupted, not cancelled: a cancel's snapshot of the old simulation would reach the UI after the reset was
  // asked for (and before the placed garment's).
  m_worker->interrupt();
  QMetaObject::invokeMethod(m_worker, &SimulationWorker::reset, Qt::QueuedConnection);
}

void SimulationController::cancel() {
  m_worker->cancel();
}

}  // namespace drape::qt
