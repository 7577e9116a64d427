#include "drape/sim/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "drape/collision/avatar_collider.h"
#include "drape/core/input_error.h"
#include "drape/core/percentile.h"
#include "drape/garment/garment_transfer.h"
#include "drape/geometry/strain.h"
#include "drape/io/garment_state.h"
#include "drape/scene/pins.h"
#include "drape/sim/snapshot_builder.h"
#include "sim/cloth_model_builder.h"
#include "sim/contact_terms.h"
#include "sim/exploded_state.h"
#include "sim/newton_stage.h"

namespace drape {

const char* toString(StepStatus status) {
  switch (status) {
    case StepStatus::Converged: return "Converged";
    case StepStatus::MaxIterations: return "MaxIterations";
    case StepStatus::Diverged: return "Diverged";
    case StepStatus::Cancelled: return "Cancelled";
  }
  return "?";
}

namespace {

// |V| x 3 rows of a flat 3|V| vector.
Eigen::MatrixX3d rowsOf(const Eigen::VectorXd& flat) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(flat.data(), flat.size() / 3, 3);
}

// The flat 3|V| vector of |V| x 3 rows (no rows: empty).
Eigen::VectorXd flatOf(const Eigen::MatrixX3d& rows) {
  Eigen::VectorXd flat(3 * rows.rows());
  for (Eigen::Index v = 0; v < rows.rows(); ++v) flat.segment<3>(3 * v) = rows.row(v).transpose();
  return flat;
}

// How long the full pipeline's preview must stay below its hand-over speed, s (as the drape's early-stop window).
constexpr double kHandOverWindow = 0.1;

// `from` on `to`'s mesh: unchanged when `to` is the mesh `from` is on, else carried through the pattern coordinates.
// Nothing when it cannot be carried (the state is not on from.garment, or the meshes are not of one pattern).
std::optional<ResumeState> carriedTo(const ResumeState& from, const Garment& to) {
  const Garment& mesh = *from.garment;
  if (from.vertexCount != mesh.vertexCount()) return std::nullopt;
  ResumeState out = from;
  out.garment.reset();
  if (mesh.vertexCount() == to.vertexCount() && mesh.triangles == to.triangles) return out;
  Eigen::SparseMatrix<double, Eigen::RowMajor> t;
  try {
    t = garmentTransfer(mesh, to);
  } catch (const std::invalid_argument&) {
    return std::nullopt;
  }
  out.positions = t * from.positions;
  out.velocities = t * from.velocities;
  if (from.previewPositions.rows() == mesh.vertexCount()) out.previewPositions = t * from.previewPositions;
  out.vertexCount = to.vertexCount();
  return out;
}

}  // namespace

// What the stages share: the garment's cloth model and the merged collider.
struct Simulation::Model {
  model::ClothModel cloth;
  std::shared_ptr<const collision::AvatarCollider> collider;
};

ResumeState startStateAt(StagePlan plan, const Eigen::MatrixX3d& positions) {
  ResumeState state;
  state.vertexCount = static_cast<int>(positions.rows());
  state.positions = positions;
  state.velocities = Eigen::MatrixX3d::Zero(positions.rows(), 3);
  state.stage = plan == StagePlan::Drape ? Stage::Drape : Stage::Preview;
  if (state.stage == Stage::Drape) state.previewPositions = positions;
  return state;
}

std::unique_ptr<Simulation> simulationFromStateFile(Scene scene, const std::filesystem::path& file) {
  const GarmentState state = readGarmentState(file);
  const StagePlan plan = simulationSettingsFrom(scene).plan;
  auto simulation = std::make_unique<Simulation>(std::move(scene), startStateAt(plan, state.positions));
  checkGarmentState(state, simulation->garment(), file);
  return simulation;
}

Simulation::Simulation(Scene scene) : m_scene(std::move(scene)) {
  build(nullptr);
}

Simulation::Simulation(Scene scene, const ResumeState& from) : m_scene(std::move(scene)) {
  build(&from);
}

Simulation::~Simulation() = default;

void Simulation::build(const ResumeState* from) {
  m_settings = simulationSettingsFrom(m_scene);
  Diagnostics diagnostics;
  m_garment = buildSceneGarment(m_scene, &diagnostics);
  m_scene.diagnostics.append(diagnostics);
  m_pinned = resolvePins(m_scene, m_garment);
  m_colliderMesh = mergedColliders(m_scene);
  m_model = std::make_unique<Model>();
  m_model->cloth = buildClothModel(m_scene, m_garment, m_pinned, m_settings.gravity);
  if (m_colliderMesh.triangleCount() > 0)
    m_model->collider = std::make_shared<const collision::AvatarCollider>(m_colliderMesh);
  const StagePlan plan = m_settings.plan;
  const bool runsPreview = plan == StagePlan::Preview || plan == StagePlan::Full;
  std::optional<ResumeState> carried;
  if (from && from->garment) {
    carried = carriedTo(*from, m_garment);
    from = carried ? &*carried : nullptr;
  }
  if (from && from->vertexCount != m_garment.vertexCount()) from = nullptr;  // re-meshed: start over
  m_resumed = from != nullptr;
  if (runsPreview && (!from || from->stage == Stage::Preview)) {
    startPreview(from);
  } else if (from && from->stage == Stage::Drape && from->previewPositions.rows() > 0) {
    // A drape restarts from the state the preview handed over, at rest, with its own time budget.
    startDrape(from->previewPositions, Eigen::MatrixX3d(), from->previewTime);
    m_drapeOwnBudget = true;
  } else {
    m_resumed = false;  // a drape that had started from the placed garment starts there again
    startDrape(Eigen::MatrixX3d(), Eigen::MatrixX3d(), 0.0);
  }
  m_sceneBox.setEmpty();
  for (Eigen::Index v = 0; v < m_colliderMesh.vertices.rows(); ++v)
    m_sceneBox.extend(m_colliderMesh.vertices.row(v).transpose());
  for (Eigen::Index v = 0; v < m_model->cloth.positions.size() / 3; ++v)
    m_sceneBox.extend(m_model->cloth.positions.segment<3>(3 * v));
  const Eigen::MatrixX3d start = positions();
  for (Eigen::Index v = 0; v < start.rows(); ++v) m_sceneBox.extend(start.row(v).transpose());
}

void Simulation::startPreview(const ResumeState* from) {
  StageStart start;
  if (from) {
    start.positions = flatOf(from->positions);
    start.velocities = flatOf(from->velocities);
    start.time = from->time;
  }
  // The preview's quasi-Newton steps follow the contour; the drape's and the settling's Newton steps hold its pull.
  m_stage = makePreviewStage(
      m_model->cloth, m_settings,
      makeContactTerms(m_settings.contact, m_scene, m_garment, m_model->collider, newton::ContourPull::Followed), start,
      from == nullptr);
  m_stageStart = start.time;
  m_settledSince = -1.0;
  m_settling = false;
  m_atRest = false;
  if (m_dragVertex >= 0) m_stage->setDrag(m_dragVertex, m_dragTarget);
}

void Simulation::startDrape(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3d& velocities, double time) {
  StageStart start;
  start.positions = flatOf(positions);
  start.velocities = flatOf(velocities);
  start.time = time;
  m_handOver = positions;
  m_handOverTime = time;
  m_stage = makeDrapeStage(m_model->cloth, m_settings,
                           makeContactTerms(m_settings.contact, m_scene, m_garment, m_model->collider,
                                            newton::ContourPull::HeldOverTheStep),
                           start, positions.rows() == 0);
  m_stageStart = time;
  m_atRest = false;
  if (m_dragVertex >= 0) m_stage->setDrag(m_dragVertex, m_dragTarget);
}

bool Simulation::previewSettled(const StepReport& report, const Eigen::VectorXd& before) {
  const bool stepped = report.status == StepStatus::Converged || report.status == StepStatus::MaxIterations;
  // Speeds of the step's motion, not the velocities carried on (zeroed while the preview relaxes).
  bool slow = false;
  if (stepped && !report.relaxing && report.h > 0.0 && m_dragVertex < 0) {
    const Eigen::VectorXd& x = m_stage->positions();
    std::vector<double> speeds(static_cast<size_t>(x.size() / 3));
    for (size_t i = 0; i < speeds.size(); ++i)
      speeds[i] = (x.segment<3>(3 * i) - before.segment<3>(3 * i)).norm() / report.h;
    slow = percentile(std::move(speeds), 0.99) < m_settings.preview.handoffSpeed;
  }
  if (!slow)
    m_settledSince = -1.0;
  else if (m_settledSince < 0.0)
    m_settledSince = time();
  return m_settledSince >= 0.0 && time() - m_settledSince >= kHandOverWindow;
}

void Simulation::startSettling() {
  StageStart start;
  start.positions = m_stage->positions();
  start.velocities = m_stage->velocities();
  start.time = m_stage->time();
  m_stage = makeSettleStage(m_model->cloth, m_settings,
                            makeContactTerms(m_settings.contact, m_scene, m_garment, m_model->collider,
                                             newton::ContourPull::HeldOverTheStep),
                            start);
  m_settling = true;
  m_atRest = false;
  if (m_dragVertex >= 0) m_stage->setDrag(m_dragVertex, m_dragTarget);
}

void Simulation::setDrag(int vertex, const Eigen::Vector3d& target) {
  if (vertex >= m_garment.vertexCount()) throw std::invalid_argument("drag: vertex index out of range");
  m_dragVertex = vertex < 0 ? -1 : vertex;
  m_dragTarget = target;
  if (m_settling && m_dragVertex >= 0) {  // pulled again: the garment moves, and L-BFGS takes the steps again
    const ResumeState now = resumeState();
    startPreview(&now);
  }
  m_stage->setDrag(m_dragVertex, target);
  if (m_dragVertex >= 0) m_atRest = false;  // a pulled garment is not at rest
}

ResumeState Simulation::resumeState() const {
  ResumeState r;
  r.stage = stage();
  r.vertexCount = m_garment.vertexCount();
  r.positions = positions();
  r.velocities = rowsOf(m_stage->velocities());
  r.time = time();
  r.previewPositions = m_handOver;
  r.previewTime = m_handOverTime;
  return r;
}

Stage Simulation::stage() const {
  return m_stage->stage();
}

std::vector<std::string> Simulation::terms() const {
  return m_stage->terms();
}

const collision::AvatarCollider* Simulation::collider() const {
  return m_model->collider.get();
}

double Simulation::time() const {
  return m_stage->time();
}

Eigen::MatrixX3d Simulation::positions() const {
  if (!m_divergedReason.empty()) return m_lastGood;
  return rowsOf(m_stage->positions());
}

void Simulation::requestCancel() {
  m_stage->requestCancel();
}

void Simulation::clearCancel() {
  m_stage->clearCancel();
}

bool Simulation::finished() const {
  return !endReason().empty();
}

std::string Simulation::endReason() const {
  const bool previewOnly = m_settings.plan == StagePlan::Preview;
  // A preview that hands over to the drape is never at rest itself: the drape follows.
  if (m_atRest && (stage() == Stage::Drape || previewOnly)) return "AtRest";
  // A drape started from a preview's state (the GUI's Drape after its Preview) has solver.max_sim_time of its own: a
  // preview that ran to the limit would leave it none.
  const double start = m_drapeOwnBudget && stage() == Stage::Drape ? m_handOverTime : 0.0;
  if (time() - start >= m_settings.maxSimTime - 1e-12) return "MaxSimTime";
  if (m_steps >= m_settings.maxSteps) return "MaxSteps";
  return "";
}

StepReport Simulation::step() {
  const auto start = std::chrono::steady_clock::now();
  StepReport report;
  if (!m_divergedReason.empty()) {  // exploded: nothing steps on from there
    report.status = StepStatus::Diverged;
    report.stage = stage();
    report.time = time();
    return report;
  }
  m_lastGood = positions();
  const Eigen::VectorXd before = m_stage->positions();
  report = m_stage->step();
  ++m_steps;
  // The stage's own rest test: the same for the preview as for the drape, on the same model.
  m_atRest = m_stage->atRest() && m_dragVertex < 0;
  report.atRest = m_atRest;
  const Eigen::MatrixX3d x = positions();
  const Eigen::VectorXd stretch = triangleStretch(m_garment.rest, x, m_garment.triangles);
  report.maxStrain = stretch.size() ? stretch.maxCoeff(&report.maxStrainTriangle) : 0.0;
  if (report.status != StepStatus::Diverged && report.status != StepStatus::Cancelled) {
    std::string reason = explodedReason(m_garment, x, stretch, m_sceneBox, std::abs(m_settings.gravity), report.time);
    if (!reason.empty()) {
      report.status = StepStatus::Diverged;
      m_divergedReason = std::move(reason);
    }
  }
  if (report.stage == Stage::Preview && !m_settling && m_divergedReason.empty() &&
      report.status != StepStatus::Cancelled) {
    const bool settled = previewSettled(report, before);
    const bool timeUp = time() - m_stageStart >= m_settings.preview.maxTime - 1e-12;
    if (m_settings.plan == StagePlan::Full && (settled || timeUp || report.status == StepStatus::Diverged)) {
      // The drape goes on from the preview's positions, velocities and time: nothing else carries over.
      startDrape(x, rowsOf(m_stage->velocities()), time());
    } else if (m_settings.plan == StagePlan::Preview && settled) {
      startSettling();
    }
  }
  report.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m_profile.add(report);
  m_lastStep = report;
  return report;
}

void PhaseProfile::add(const StepReport& r) {
  assembly += r.assemblyTime;
  linearSolve += r.linearSolveTime;
  contactQueries += r.contactQueryTime;
  lineSearch += r.gradientTime;
  bookkeeping += std::max(0.0, r.wallTime - r.assemblyTime - r.linearSolveTime - r.contactQueryTime - r.gradientTime);
}

Snapshot Simulation::snapshot() const {
  Snapshot s = makeSnapshot(m_scene, m_garment, positions());
  s.triangleDomain = m_stage->triangleDomains();
  s.vertexContact = m_stage->contactMask();
  s.time = time();
  s.stage = m_atRest ? Stage::Done : (m_steps == 0 && !m_resumed ? Stage::Placed : stage());
  return s;
}

}  // namespace drape
