#include "drape/qt/simulation_worker.h"

#include <QMetaObject>
#include <exception>

namespace drape::qt {

const char* toString(RunState state) {
  switch (state) {
    case RunState::Empty: return "empty";
    case RunState::Ready: return "ready";
    case RunState::Running: return "running";
    case RunState::Paused: return "paused";
    case RunState::Finished: return "finished";
    case RunState::Cancelled: return "cancelled";
  }
  return "?";
}

SimulationWorker::SimulationWorker(QObject* parent) : QObject(parent) {}

SimulationWorker::~SimulationWorker() = default;

std::shared_ptr<Simulation> SimulationWorker::current() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  return m_simulation;
}

void SimulationWorker::cancel() {
  m_running.store(false);
  if (auto simulation = current()) {
    simulation->requestCancel();
    // A step in progress reports Cancelled; between steps, the state changes here.
    setState(RunState::Cancelled);
  }
}

void SimulationWorker::setState(RunState state) {
  if (m_state.exchange(state) != state) emit runStateChanged(state);
}

void SimulationWorker::sendSnapshot() {
  auto simulation = current();
  if (!simulation) return;
  m_lastSnapshot = std::chrono::steady_clock::now();
  emit snapshotReady(std::make_shared<const Snapshot>(simulation->snapshot()));
}

void SimulationWorker::setSimulation(std::shared_ptr<Simulation> simulation) {
  m_running.store(false);
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_simulation = std::move(simulation);
  }
  if (!current()) {
    setState(RunState::Empty);
    return;
  }
  m_state.store(RunState::Empty);  // always announce the new simulation
  setState(RunState::Ready);
  sendSnapshot();
}

void SimulationWorker::start() {
  auto simulation = current();
  if (!simulation || m_state.load() == RunState::Cancelled || m_running.load()) return;
  if (simulation->finished()) {
    setState(RunState::Finished);
    return;
  }
  m_running.store(true);
  setState(RunState::Running);
  scheduleStep();
}

void SimulationWorker::scheduleStep() {
  if (m_stepQueued) return;  // one chain of step events at a time, however often start/pause alternate
  m_stepQueued = true;
  QMetaObject::invokeMethod(this, &SimulationWorker::stepOnce, Qt::QueuedConnection);
}

void SimulationWorker::pause() {
  if (!m_running.exchange(false)) return;
  setState(RunState::Paused);
  sendSnapshot();
}

void SimulationWorker::reset() {
  m_running.store(false);
  auto old = current();
  if (!old) return;
  try {
    auto fresh = std::make_shared<Simulation>(old->scene());
    setSimulation(std::move(fresh));
  } catch (const std::exception& e) {
    emit errorOccurred(QStringLiteral("Reset failed: %1").arg(QString::fromStdString(e.what())));
  }
}

void SimulationWorker::stepOnce() {
  m_stepQueued = false;
  if (!m_running.load()) return;
  auto simulation = current();
  if (!simulation) return;
  const StepReport report = simulation->step();
  emit stepReported(report);
  if (report.status == StepStatus::Cancelled) {
    m_running.store(false);
    setState(RunState::Cancelled);
    sendSnapshot();
    return;
  }
  if (report.status == StepStatus::Diverged) {
    m_running.store(false);
    setState(RunState::Paused);
    sendSnapshot();
    emit errorOccurred(QStringLiteral("The drape diverged at t = %1 s (step %2); the last good state is kept.")
                           .arg(report.time, 0, 'g', 4)
                           .arg(simulation->steps()));
    return;
  }
  if (simulation->finished()) {
    m_running.store(false);
    setState(RunState::Finished);
    sendSnapshot();
    return;
  }
  if (!m_running.load()) return;  // paused or cancelled while stepping: that slot sent the snapshot
  const auto since = std::chrono::steady_clock::now() - m_lastSnapshot;
  if (since >= std::chrono::milliseconds(m_snapshotIntervalMs.load())) sendSnapshot();
  scheduleStep();
}

}  // namespace drape::qt
