#include "drape/qt/simulation_worker.h"

#include <QMetaObject>
#include <exception>
#include <stdexcept>

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

Stage SimulationWorker::stage() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  return m_stage.value_or(Stage::Placed);
}

std::optional<ResumeState> SimulationWorker::latestResumeState() const {
  std::lock_guard<std::mutex> lock(m_mutex);
  return m_resume;
}

void SimulationWorker::interrupt() {
  ++m_cancelGeneration;
  m_running.store(false);
  if (auto simulation = current()) simulation->requestCancel();
}

void SimulationWorker::cancel() {
  m_cancelPending.store(true);
  interrupt();
  // Queued behind a step in progress: its report reaches the UI before the state change.
  QMetaObject::invokeMethod(this, &SimulationWorker::finishCancel, Qt::QueuedConnection);
}

void SimulationWorker::finishCancel() {
  if (!m_cancelPending.exchange(false) || !current()) return;
  setState(RunState::Cancelled);
  sendSnapshot();
}

void SimulationWorker::setState(RunState state) {
  if (m_state.exchange(state) != state) emit runStateChanged(state);
}

void SimulationWorker::updateStage() {
  auto simulation = current();
  if (!simulation) return;
  const Stage stage = simulation->steps() == 0 && !simulation->resumed() ? Stage::Placed : simulation->stage();
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (stage == m_stage) return;
    m_stage = stage;
  }
  emit stageChanged(stage);
}

void SimulationWorker::publishResumeState() {
  auto simulation = current();
  std::optional<ResumeState> resume;
  if (simulation && (simulation->steps() > 0 || simulation->resumed())) resume = simulation->resumeState();
  std::lock_guard<std::mutex> lock(m_mutex);
  m_resume = std::move(resume);
}

void SimulationWorker::sendSnapshot() {
  auto simulation = current();
  if (!simulation) return;
  m_lastSnapshot = std::chrono::steady_clock::now();
  emit snapshotReady(std::make_shared<const Snapshot>(simulation->snapshot()));
}

void SimulationWorker::replace(std::shared_ptr<Simulation> simulation) {
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_simulation = std::move(simulation);
  }
  auto fresh = current();
  if (fresh && m_dragVertex >= 0) {
    if (m_dragVertex < fresh->garment().vertexCount())
      fresh->setDrag(m_dragVertex, m_dragTarget);
    else
      m_dragVertex = -1;
  }
  updateStage();
  publishResumeState();
}

void SimulationWorker::setSimulation(std::shared_ptr<Simulation> simulation) {
  m_running.store(false);
  m_dragVertex = -1;  // another garment: the grabbed index means nothing there
  replace(std::move(simulation));
  if (!current()) {
    setState(RunState::Empty);
    return;
  }
  m_state.store(RunState::Empty);  // always announce the new simulation
  setState(RunState::Ready);
  sendSnapshot();
}

void SimulationWorker::continueWith(std::shared_ptr<Simulation> simulation) {
  if (!simulation) return;
  const bool running = m_running.load();
  replace(std::move(simulation));
  if (running) {
    setState(RunState::Running);
    scheduleStep();  // the pending step event, if any, now steps the new simulation
  } else {
    m_state.store(RunState::Empty);  // announce the new simulation even when the state name is the same
    setState(current()->resumed() ? RunState::Paused : RunState::Ready);
  }
  sendSnapshot();
}

bool SimulationWorker::rebuild(const std::string& stage, const ResumeState* from) {
  auto old = current();
  if (!old) return false;
  try {
    Scene scene = old->scene();
    scene.settings.set("solver.stage", stage, "simulation");
    auto fresh = from ? std::make_shared<Simulation>(std::move(scene), *from)
                      : std::make_shared<Simulation>(std::move(scene));
    replace(std::move(fresh));
    sendSnapshot();
    return true;
  } catch (const std::exception& e) {
    emit errorOccurred(QStringLiteral("Cannot start the %1: %2")
                           .arg(QString::fromStdString(stage), QString::fromStdString(e.what())));
    return false;
  }
}

void SimulationWorker::start(int generation) {
  auto simulation = current();
  if (!simulation || m_running.load() || cancelledSince(generation)) return;
  simulation->clearCancel();  // after a cancel the kept state continues
  m_cancelPending.store(false);
  if (simulation->finished()) {
    setState(RunState::Finished);
    return;
  }
  m_running.store(true);
  setState(RunState::Running);
  scheduleStep();
}

void SimulationWorker::startPreview(int generation) {
  auto simulation = current();
  if (!simulation || m_running.load() || cancelledSince(generation)) return;
  const Stage now = stage();
  if (now == Stage::Drape) return;  // the drape has started: Reset goes back to the placed garment
  if (simulation->scene().settings.stagePlan() != StagePlan::Preview) {
    if (now == Stage::Placed) {
      if (!rebuild("preview", nullptr)) return;
    } else {  // a "full" scene still in its preview: continue it as a preview only
      const ResumeState from = simulation->resumeState();
      if (!rebuild("preview", &from)) return;
    }
  }
  start(generation);
}

void SimulationWorker::startDrape(int generation) {
  auto simulation = current();
  if (!simulation || m_running.load() || cancelledSince(generation)) return;
  if (simulation->stage() == Stage::Preview) {
    if (stage() == Stage::Placed) {
      if (!rebuild("drape", nullptr)) return;
    } else {
      // The drape starts from the preview state (the engine resets the velocities).
      ResumeState from = simulation->resumeState();
      from.stage = Stage::Drape;
      from.previewPositions = from.positions;
      from.previewTime = from.time;
      if (!rebuild("drape", &from)) return;
    }
  }
  start(generation);
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
    const int drag = m_dragVertex;
    setSimulation(std::move(fresh));
    m_dragVertex = drag;  // same garment: a vertex still held by the mouse stays held
  } catch (const std::exception& e) {
    emit errorOccurred(QStringLiteral("Reset failed: %1").arg(QString::fromStdString(e.what())));
  }
}

void SimulationWorker::setDrag(int vertex, Eigen::Vector3d target) {
  m_dragVertex = vertex < 0 ? -1 : vertex;
  m_dragTarget = target;
  auto simulation = current();
  if (!simulation) return;
  try {
    simulation->setDrag(m_dragVertex, target);
  } catch (const std::invalid_argument&) {
    m_dragVertex = -1;  // a stale index from another garment: ignore it
  }
}

void SimulationWorker::stepOnce() {
  m_stepQueued = false;
  if (!m_running.load()) return;  // paused or cancelled between two steps (finishCancel shows a cancel)
  auto simulation = current();
  if (!simulation) return;
  const Stage before = simulation->stage();
  const StepReport report = simulation->step();
  emit stepReported(report);
  // A stage that settles says so: the preview at rest is the drape's model at rest; the hand-over says when.
  if (report.atRest)
    emit infoOccurred(QStringLiteral("The %1 is at rest at t = %2 s (step %3)")
                          .arg(stageName(report.stage))
                          .arg(report.time, 0, 'g', 4)
                          .arg(simulation->steps()));
  else if (simulation->stage() != before)
    emit infoOccurred(QStringLiteral("The drape takes over from the preview at t = %1 s").arg(simulation->time(), 0, 'g', 4));
  updateStage();
  if (report.status != StepStatus::Cancelled) publishResumeState();
  if (report.status == StepStatus::Cancelled) {
    m_running.store(false);
    m_cancelPending.store(false);  // shown here
    setState(RunState::Cancelled);
    sendSnapshot();
    return;
  }
  if (report.status == StepStatus::Diverged) {
    m_running.store(false);
    setState(RunState::Paused);
    sendSnapshot();
    // Why, when the garment exploded (Simulation::divergedReason); else the solver found no step that converges.
    const std::string& why = simulation->divergedReason();
    emit errorOccurred(QStringLiteral("The %1 diverged at t = %2 s (step %3)%4; the last good state is kept.")
                           .arg(stageName(report.stage))
                           .arg(report.time, 0, 'g', 4)
                           .arg(simulation->steps())
                           .arg(why.empty() ? QString() : QStringLiteral(": ") + QString::fromStdString(why)));
    return;
  }
  if (simulation->finished()) {
    m_running.store(false);
    emit qualityReported(checkDrapeQuality(*simulation, simulation->endReason()));
    setState(RunState::Finished);
    sendSnapshot();
    return;
  }
  if (!m_running.load()) return;  // paused (that slot sent the snapshot) or cancelled (finishCancel follows)
  const auto since = std::chrono::steady_clock::now() - m_lastSnapshot;
  if (since >= std::chrono::milliseconds(m_snapshotIntervalMs.load())) sendSnapshot();
  scheduleStep();
}

}  // namespace drape::qt
