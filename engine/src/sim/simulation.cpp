#include "drape/sim/simulation.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "drape/collision/avatar_collider.h"
#include "drape/core/input_error.h"
#include "drape/core/percentile.h"
#include "drape/garment/garment_builder.h"
#include "drape/garment/garment_transfer.h"
#include "drape/geometry/strain.h"
#include "drape/io/garment_state.h"
#include "drape/newton/body_forces.h"
#include "drape/pd/preview_fabric.h"
#include "drape/pd/preview_solver.h"
#include "drape/scene/pins.h"
#include "drape/sim/snapshot_builder.h"
#include "sim/cloth_model_builder.h"
#include "sim/contact_terms.h"
#include "sim/exploded_state.h"
#include "sim/simulation_solver.h"

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

template <class Status>
StepStatus toStepStatus(Status s) {
  switch (s) {
    case Status::Converged: return StepStatus::Converged;
    case Status::MaxIterations: return StepStatus::MaxIterations;
    case Status::Diverged: return StepStatus::Diverged;
    case Status::Cancelled: return StepStatus::Cancelled;
  }
  return StepStatus::Diverged;
}

// |V| x 3 rows of a flat 3|V| vector.
Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> rowsOf(const Eigen::VectorXd& flat) {
  return {flat.data(), flat.size() / 3, 3};
}

// Moves every vertex inside the collider (found within `reach` of its surface) to `thickness` outside, along the
// surface normal.
void liftOutOf(const collision::AvatarCollider& collider, double thickness, double reach, Eigen::MatrixX3d& x) {
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    collision::SurfacePoint sp;
    if (collider.closest(x.row(v).transpose(), sp, reach) && sp.signedDistance < 0.0)
      x.row(v) = (sp.closest + thickness * sp.normal).transpose();
  }
}

}  // namespace

double previewCourantLimitOf(const Scene& scene) {
  double limit = scene.settings.number("solver.preview.courant_limit");
  const double pipeline = scene.settings.number("solver.preview.pipeline_courant_limit");
  if (scene.settings.stagePlan() == StagePlan::Full && pipeline > 0.0 && (limit <= 0.0 || pipeline < limit))
    limit = pipeline;
  return limit;
}

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
  const std::string stage = scene.settings.text("solver.stage");
  const StagePlan plan = scene.settings.stagePlan();
  auto simulation = std::make_unique<Simulation>(std::move(scene), startStateAt(plan, state.positions));
  checkGarmentState(state, simulation->garment(), file);
  if (!simulation->resumed()) {
    const std::string why = simulation->previewFailure();
    throw InputError(file.string() + ": " +
                     (why.empty() ? "the " + stage + " stage cannot start from this state" : why));
  }
  return simulation;
}

Simulation::Simulation(Scene scene) : m_scene(std::move(scene)) { build(nullptr); }

Simulation::Simulation(Scene scene, const ResumeState& from) : m_scene(std::move(scene)) { build(&from); }

Simulation::~Simulation() = default;

void Simulation::build(const ResumeState* from) {
  Diagnostics diagnostics;
  m_garment = buildSceneGarment(m_scene, &diagnostics);
  m_scene.diagnostics.append(diagnostics);
  m_pinned = resolvePins(m_scene, m_garment);
  m_colliderMesh = mergedColliders(m_scene);
  m_solver = std::make_unique<Solver>();
  m_solver->model = buildClothModel(m_scene, m_garment, m_pinned);
  m_solver->masses = newton::lumpedVertexMasses(m_solver->model);
  m_courantLimit = previewCourantLimitOf(m_scene);
  m_courantNumber = pd::courantNumber(m_solver->model, m_scene.settings.number("solver.preview.time_step"));
  if (m_colliderMesh.triangleCount() > 0)
    m_solver->collider = std::make_shared<const collision::AvatarCollider>(m_colliderMesh);
  const StagePlan plan = m_scene.settings.stagePlan();
  const bool runsPreview = plan == StagePlan::Preview || plan == StagePlan::Full;
  if (from && from->vertexCount != m_garment.vertexCount()) from = nullptr;  // re-meshed: start over
  if (from && from->assembling) from = nullptr;  // not sewn yet: the assembly starts over
  m_resumed = from != nullptr;
  if (runsPreview && quasiNewtonMethod() && (!from || from->stage == Stage::Preview)) {
    startQuasiNewtonPreview(from);
  } else if (from && from->stage == Stage::Preview && runsPreview) {
    model::ClothModel model = m_solver->model;
    for (int v = 0; v < m_garment.vertexCount(); ++v) {
      model.positions.segment<3>(3 * v) = from->positions.row(v).transpose();
    }
    model.velocities.resize(3 * m_garment.vertexCount());
    for (int v = 0; v < m_garment.vertexCount(); ++v)
      model.velocities.segment<3>(3 * v) = from->velocities.row(v).transpose();
    model.startTime = from->time;
    m_solver->previewOffset = from->time;
    // A softened preview (the full pipeline's, or one that started over softer after a tear) goes on that soft: its
    // state has not seen the fabric's own stiffness.
    if (from->previewCourantLimit > 0.0 && (m_courantLimit <= 0.0 || m_courantLimit > from->previewCourantLimit))
      m_courantLimit = from->previewCourantLimit;
    m_targetsFreed = from->previewTargetsFreed;
    m_solver->preview = std::make_unique<pd::PreviewSolver>(model, previewSettings(), m_solver->collider);
  } else if (from && from->stage == Stage::Drape) {
    m_resumed = from->previewPositions.rows() > 0;  // else the drape had started from the placed garment
    if (m_resumed) {
      const Eigen::VectorXd stretch = triangleStretch(m_garment.rest, from->previewPositions, m_garment.triangles);
      StepReport saved;
      saved.time = from->previewTime;
      saved.maxStrain = stretch.size() ? stretch.maxCoeff(&saved.maxStrainTriangle) : 0.0;
      m_previewFailure = tearReason(saved, from->previewPositions);
      m_resumed = m_previewFailure.empty();
    }
    startDrape(m_resumed ? from->previewPositions : Eigen::MatrixX3d(), m_resumed ? from->previewTime : 0.0);
    m_drapeOwnBudget = m_resumed;
  } else if (runsPreview) {
    m_resumed = false;
    startPreview();
  } else {
    m_resumed = false;
    startDrape(Eigen::MatrixX3d(), 0.0);
  }
  m_sceneBox.setEmpty();
  for (Eigen::Index v = 0; v < m_colliderMesh.vertices.rows(); ++v)
    m_sceneBox.extend(m_colliderMesh.vertices.row(v).transpose());
  for (Eigen::Index v = 0; v < m_solver->model.positions.size() / 3; ++v)
    m_sceneBox.extend(m_solver->model.positions.segment<3>(3 * v));
  const Eigen::MatrixX3d start = positions();
  for (Eigen::Index v = 0; v < start.rows(); ++v) m_sceneBox.extend(start.row(v).transpose());
}

pd::PreviewSettings Simulation::previewSettings() const {
  pd::PreviewSettings settings = previewSettingsFrom(m_scene);
  settings.courantLimit = m_courantLimit;
  if (m_targetsFreed) settings.holdTargetsStep = 0.0;
  return settings;
}

void Simulation::startPreview() {
  m_solver->assembly.reset();
  m_solver->preview.reset();
  // A tear found in the step that handed over has already started the drape: starting over drops it.
  m_solver->newton.reset();
  m_solver->quasiNewtonPreview = false;
  m_solver->preconditioner.reset();
  m_solver->previewPositions.resize(0, 3);
  m_solver->previewTime = 0.0;
  m_atRest = false;
  m_solver->previewOffset = 0.0;
  m_restSince = -1.0;
  m_overshootSince = -1.0;
  if (!startAssembly())
    m_solver->preview = std::make_unique<pd::PreviewSolver>(m_solver->model, previewSettings(), m_solver->collider);
  else if (m_dragVertex >= 0)
    m_solver->assembly->preview->setDrag(assemblyVertex(m_dragVertex), m_dragTarget);
  if (m_solver->preview && m_dragVertex >= 0) m_solver->preview->setDrag(m_dragVertex, m_dragTarget);
}

bool Simulation::startAssembly() {
  const double edge = m_scene.settings.number("solver.preview.assembly_edge_length");
  if (edge <= 0.0 || edge < 1.5 * m_scene.settings.number("mesh.target_edge_length")) return false;
  if (m_garment.stitchPairs.empty() && m_garment.edgeStitches.empty()) return false;  // nothing to sew
  // A vertex pin names a vertex of the scene's own mesh.
  for (const PinSpec& pin : m_scene.pins)
    if (!pin.vertices.empty()) return false;
  Scene coarse = m_scene;
  coarse.settings.set("mesh.target_edge_length", std::to_string(edge), "solver.preview.assembly_edge_length");
  auto assembly = std::make_unique<Solver::Assembly>();
  try {
    assembly->garment = buildGarment(coarse.pattern, meshingOptions(coarse));
  } catch (const InputError&) {
    return false;  // the pattern does not mesh this coarsely: the preview sews the scene's own mesh
  }
  const model::ClothModel model = buildClothModel(coarse, assembly->garment, resolvePins(coarse, assembly->garment));
  assembly->masses = newton::lumpedVertexMasses(model);
  assembly->toGarment = garmentTransfer(assembly->garment, m_garment);
  assembly->preview = std::make_unique<pd::PreviewSolver>(model, previewSettings(), m_solver->collider);
  m_solver->assembly = std::move(assembly);
  return true;
}

int Simulation::assemblyVertex(int vertex) const {
  if (vertex < 0) return -1;
  int best = -1;
  double weight = -1.0;
  using Row = Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator;
  for (Row it(m_solver->assembly->toGarment, vertex); it; ++it) {
    if (it.value() > weight) {
      weight = it.value();
      best = static_cast<int>(it.col());
    }
  }
  return best;
}

void Simulation::finishAssembly() {
  Solver::Assembly& a = *m_solver->assembly;
  const double start = a.preview->time();
  Eigen::MatrixX3d x = a.toGarment * rowsOf(a.preview->positions());
  const Eigen::MatrixX3d v = a.toGarment * rowsOf(a.preview->velocities());
  // A garment vertex between coarse vertices can sit inside a curved body: lift it out before the contact
  // constraints take over (within the coarse edge length: the deepest a coarse triangle's interior reaches).
  if (m_solver->collider) {
    liftOutOf(*m_solver->collider, contactThickness(),
              m_scene.settings.number("solver.preview.assembly_edge_length"), x);
  }
  m_solver->assembly.reset();
  const bool timeUp = start >= previewMaxTime() - 1e-12;
  if (m_scene.settings.stagePlan() == StagePlan::Full && timeUp) {
    startDrape(x, start);
    return;
  }
  model::ClothModel model = m_solver->model;
  model.velocities.resize(3 * m_garment.vertexCount());
  for (int i = 0; i < m_garment.vertexCount(); ++i) {
    model.positions.segment<3>(3 * i) = x.row(i).transpose();
    model.velocities.segment<3>(3 * i) = v.row(i).transpose();
  }
  model.startTime = start;
  m_solver->previewOffset = start;
  m_solver->preview = std::make_unique<pd::PreviewSolver>(model, previewSettings(), m_solver->collider);
  if (m_dragVertex >= 0) m_solver->preview->setDrag(m_dragVertex, m_dragTarget);
}

void Simulation::startDrape(const Eigen::MatrixX3d& positions, double time) {
  model::ClothModel model = m_solver->model;
  m_solver->preview.reset();
  m_solver->previewPositions = positions;
  m_solver->previewTime = time;
  m_solver->newtonOffset = time;
  m_solver->quasiNewtonPreview = false;
  m_solver->preconditioner.reset();
  if (positions.rows() > 0) {  // warm start from the preview; velocities reset
    for (int v = 0; v < m_garment.vertexCount(); ++v) model.positions.segment<3>(3 * v) = positions.row(v).transpose();
  }
  model.startTime = time;
  m_solver->contact = makeContactTerms(m_scene, m_garment, m_solver->collider);
  newton::NewtonSettings settings = newtonSettingsFrom(m_scene);
  // The relaxation settles a placed garment (seams apart, pre-stretch); the preview has already done that.
  // Its time steps may be longer: it settles a garment already near rest, whose result they barely move (docs/
  // BENCHMARKS.md, "Findings worth keeping"). They start at h_max and grow: the state the preview hands over (its
  // fabric softened) may need a short first step, and a first step at the cap is split many times.
  if (positions.rows() > 0) {
    settings.relaxation = m_scene.settings.flag("solver.newton.relaxation_after_preview");
    settings.startStep = settings.hMax;
    settings.hMax *= m_scene.settings.number("solver.newton.h_max_factor_after_preview");
  }
  m_solver->newton = std::make_unique<newton::NewtonSolver>(std::move(model), settings,
                                                            std::move(m_solver->contact.energies));
  if (m_dragVertex >= 0) m_solver->newton->setDrag(m_dragVertex, m_dragTarget);
  m_atRest = false;
}

// Without a retry (solver.preview.retry_courant_limit 0), the tear message suggests softening the preview's fabric
// above this Courant number (preview_fabric.h): 5 kept the default t-shirt whole in every fabric preset, 8 did not
// (docs/BENCHMARKS.md, "Findings worth keeping").
constexpr double kSoftenedCourant = 5.0;

double Simulation::previewMaxTime() const {
  const double maxTime = m_scene.settings.number("solver.preview.max_time");
  if (m_scene.settings.stagePlan() != StagePlan::Full || m_courantLimit <= 0.0 || m_courantNumber <= m_courantLimit)
    return maxTime;
  return std::min(maxTime, m_scene.settings.number("solver.preview.softened_max_time"));
}

double Simulation::retryCourantLimit() const {
  const double retry = m_scene.settings.number("solver.preview.retry_courant_limit");
  if (retry <= 0.0 || (m_courantLimit > 0.0 && m_courantLimit <= retry)) return 0.0;  // off, or already this soft
  return m_courantNumber > retry ? retry : 0.0;  // else softening to it would change nothing
}

bool Simulation::retriesUnheld() const {
  const Settings& s = m_scene.settings;
  return !m_targetsFreed && s.flag("solver.preview.retry_without_held_targets") &&
         s.number("solver.preview.hold_targets_step") > 0.0 && !s.flag("solver.preview.hold_contact_targets");
}

std::string Simulation::stretchedTriangle(const StepReport& report, const Eigen::MatrixX3d& x) const {
  const int t = report.maxStrainTriangle;
  if (t < 0 || t >= m_garment.triangles.rows()) return "";
  const Eigen::Vector3d centre =
      (x.row(m_garment.triangles(t, 0)) + x.row(m_garment.triangles(t, 1)) + x.row(m_garment.triangles(t, 2))) / 3.0;
  const int panel = t < m_garment.trianglePanel.size() ? m_garment.trianglePanel[t] : -1;
  const std::string name =
      panel >= 0 && panel < static_cast<int>(m_garment.panelNames.size()) ? m_garment.panelNames[panel] : "?";
  char at[200];
  std::snprintf(at, sizeof at, " (triangle %d of panel %s, at x %.3f, y %.3f, z %.3f m)", t, name.c_str(), centre.x(),
                centre.y(), centre.z());
  return at;
}

std::string Simulation::tearReason(const StepReport& report, const Eigen::MatrixX3d& x, TearOutcome then) const {
  const double limit = m_scene.settings.number("solver.preview.failure_strain");
  if (limit <= 0.0 || report.maxStrain <= limit) return "";
  const std::string where = stretchedTriangle(report, x);
  const double courant = m_courantNumber;
  std::string next = "the drape starts from the placed garment";
  if (then == TearOutcome::PreviewGoesOn)
    next = "the preview goes on, but its result is wrong: only the drape's can be trusted";
  if (then == TearOutcome::PreviewStartsOver) {
    char over[200];
    std::snprintf(over, sizeof over,
                  "the preview starts over from the placed garment with its fabric softened from Courant number %.1f "
                  "to %g (solver.preview.retry_courant_limit)",
                  courant, retryCourantLimit());
    next = over;
  }
  if (then == TearOutcome::PreviewStartsOverUnheld)
    next =
        "the preview starts over from the placed garment with its contact targets not held before it is sewn "
        "(solver.preview.retry_without_held_targets)";
  char message[600];
  std::snprintf(message, sizeof message, "the preview stretched a triangle to %.0f %% at t = %.3f s%s; %s",
                100.0 * report.maxStrain, report.time, where.c_str(), next.c_str());
  std::string said = message;
  // A fabric this stiff for its mesh and preview step closed the seams through the body (preview_fabric.h).
  const bool startsOver = then == TearOutcome::PreviewStartsOver || then == TearOutcome::PreviewStartsOverUnheld;
  if (!startsOver && m_courantLimit <= 0.0 && courant > kSoftenedCourant) {
    std::snprintf(message, sizeof message,
                  " (the fabric is stiff for this mesh and preview step, Courant number %.1f: "
                  "--set solver.preview.courant_limit=%g softens the preview's fabric)",
                  courant, kSoftenedCourant);
    said += message;
  }
  return said;
}

// The first closing's overshoots that recover stay below 1,000 % on the library scenes (the trousers: about 600 % for
// 4 ms at the default step); the two layers of the shirt over a skirt, broken in their first step, sat at 3,440 % for
// the whole quasi-static start.
constexpr double kStuckOvershoot = 4.0;  // times failure_strain
constexpr double kStuckTime = 0.003;     // s of scene time

bool Simulation::stuckOvershoot(const StepReport& report) {
  const double limit = m_scene.settings.number("solver.preview.failure_strain");
  if (limit <= 0.0 || report.maxStrain <= kStuckOvershoot * limit) {
    m_overshootSince = -1.0;
    return false;
  }
  if (m_overshootSince < 0.0) m_overshootSince = report.time - report.h;
  return report.time - m_overshootSince >= kStuckTime * (1.0 - 1e-9);
}

void Simulation::failPreviewIfTorn(const StepReport& report, const Eigen::MatrixX3d& x) {
  // While the preview starts quasi-statically, the seams' first closing may overshoot (the trousers' hems at 1/1920
  // s: 518 %, back to 45 % within 6 ms); a tear is what is left after it, or an overshoot that stays (stuckOvershoot).
  if (report.time <= m_scene.settings.number("solver.preview.relaxation_time") && !stuckOvershoot(report)) return;
  const bool previewAlone = m_scene.settings.stagePlan() == StagePlan::Preview;
  if (previewAlone && m_previewWrong) return;  // said once, at the first torn step
  const double retry = retryCourantLimit();
  TearOutcome then = retry > 0.0       ? TearOutcome::PreviewStartsOver
                     : retriesUnheld() ? TearOutcome::PreviewStartsOverUnheld
                     : previewAlone    ? TearOutcome::PreviewGoesOn
                                       : TearOutcome::DrapeFromPlaced;
  std::string reason = tearReason(report, x, then);
  if (reason.empty()) {  // not torn; a hand-over stretched this far starts over as a tear would
    reason = overstretchedHandOverReason(report, x);
    if (reason.empty()) return;
    then = TearOutcome::PreviewStartsOverUnheld;
  }
  switch (then) {
    case TearOutcome::PreviewGoesOn:
      m_previewFailure = std::move(reason);
      m_previewWrong = true;
      break;
    case TearOutcome::DrapeFromPlaced:
      m_previewFailure = std::move(reason);
      m_solver->assembly.reset();
      startDrape(Eigen::MatrixX3d(), 0.0);
      break;
    case TearOutcome::PreviewStartsOver:
      m_previewRestartReasons.push_back(std::move(reason));
      m_courantLimit = retry;
      startPreview();
      break;
    case TearOutcome::PreviewStartsOverUnheld:
      m_previewRestartReasons.push_back(std::move(reason));
      m_targetsFreed = true;
      startPreview();
      break;
  }
}

std::string Simulation::overstretchedHandOverReason(const StepReport& report, const Eigen::MatrixX3d& x) const {
  const bool handedOver = m_solver->newton && m_solver->previewPositions.rows() > 0;  // in this step
  if (!handedOver) return "";
  const double limit = m_scene.settings.number("solver.preview.handoff_strain");
  if (limit <= 0.0 || report.maxStrain <= limit || !retriesUnheld()) return "";
  char message[600];
  std::snprintf(message, sizeof message,
                "the preview was to hand over a triangle stretched to %.0f %% at t = %.3f s%s, past "
                "solver.preview.handoff_strain (%.0f %%); the preview starts over from the placed garment with its "
                "contact targets not held before it is sewn (solver.preview.retry_without_held_targets)",
                100.0 * report.maxStrain, report.time, stretchedTriangle(report, x).c_str(), 100.0 * limit);
  return message;
}

void Simulation::setDrag(int vertex, const Eigen::Vector3d& target) {
  if (vertex >= m_garment.vertexCount()) throw std::invalid_argument("drag: vertex index out of range");
  m_dragVertex = vertex < 0 ? -1 : vertex;
  m_dragTarget = target;
  if (m_solver->preview) m_solver->preview->setDrag(m_dragVertex, target);
  if (m_solver->assembly) m_solver->assembly->preview->setDrag(assemblyVertex(m_dragVertex), target);
  if (m_solver->newton) m_solver->newton->setDrag(m_dragVertex, target);
  if (m_dragVertex >= 0) m_atRest = false;  // a pulled garment is not at rest
}

ResumeState Simulation::resumeState() const {
  ResumeState r;
  r.stage = stage();
  r.vertexCount = m_garment.vertexCount();
  r.assembling = m_solver->assembly != nullptr;
  r.positions = positions();
  if (m_solver->assembly) {
    r.velocities = m_solver->assembly->toGarment * rowsOf(m_solver->assembly->preview->velocities());
  } else {
    const Eigen::VectorXd& v = m_solver->preview ? m_solver->preview->velocities() : m_solver->newton->velocities();
    r.velocities = rowsOf(v);
  }
  r.time = time();
  r.previewPositions = m_solver->previewPositions;
  r.previewTime = m_solver->previewTime;
  r.previewCourantLimit = m_courantLimit;
  r.previewTargetsFreed = m_targetsFreed;
  return r;
}

Stage Simulation::stage() const {
  return m_solver->newton && !m_solver->quasiNewtonPreview ? Stage::Drape : Stage::Preview;
}

bool Simulation::assembling() const { return m_solver->assembly != nullptr; }

std::vector<std::string> Simulation::terms() const {
  if (m_solver->newton) return m_solver->newton->energyNames();
  std::vector<std::string> t = {"pd_strain", "pd_bending", "gravity"};
  if (!m_solver->model.stitches.empty() || !m_solver->model.edgeStitches.empty()) t.push_back("pd_stitches");
  if (!m_solver->model.pinned.empty()) t.push_back("pins");
  if (m_solver->collider) t.push_back("pd_avatar_contact");
  const pd::PreviewSettings ps = previewSettings();
  if (m_solver->collider && ps.friction > 0.0) t.push_back("pd_friction");
  if (ps.selfCollision) t.push_back("pd_self_contact");
  return t;
}

double Simulation::contactThickness() const { return drape::contactThickness(m_scene); }

const collision::AvatarCollider* Simulation::collider() const { return m_solver->collider.get(); }

double Simulation::time() const {
  if (m_solver->assembly) return m_solver->assembly->preview->time();
  return m_solver->preview ? m_solver->previewOffset + m_solver->preview->time()
                           : m_solver->newtonOffset + m_solver->newton->time();
}

Eigen::MatrixX3d Simulation::positions() const {
  if (!m_divergedReason.empty()) return m_lastGood;
  if (m_solver->assembly) return m_solver->assembly->toGarment * rowsOf(m_solver->assembly->preview->positions());
  return rowsOf(m_solver->preview ? m_solver->preview->positions() : m_solver->newton->positions());
}

void Simulation::requestCancel() {
  if (m_solver->assembly) m_solver->assembly->preview->requestCancel();
  if (m_solver->preview) m_solver->preview->requestCancel();
  if (m_solver->newton) m_solver->newton->requestCancel();
}

void Simulation::clearCancel() {
  if (m_solver->assembly) m_solver->assembly->preview->clearCancel();
  if (m_solver->preview) m_solver->preview->clearCancel();
  if (m_solver->newton) m_solver->newton->clearCancel();
}

bool Simulation::previewSettled(std::vector<double> speeds, bool waiting) {
  // Settled: vertex speeds below the threshold for a 0.1 s window (as the drape's early stop). A preview that hands
  // over to the drape uses the looser hand-off speed: the drape settles the rest.
  const bool previewOnly = m_scene.settings.stagePlan() == StagePlan::Preview;
  const double restSpeed = m_scene.settings.number(previewOnly ? "solver.preview.rest_speed"
                                                               : "solver.preview.handoff_speed");
  if (!waiting && percentile(std::move(speeds), 0.99) < restSpeed && m_dragVertex < 0) {
    if (m_restSince < 0) m_restSince = time();
  } else {
    m_restSince = -1.0;
  }
  return m_restSince >= 0 && time() - m_restSince >= 0.1;
}

bool Simulation::finished() const { return !endReason().empty(); }

std::string Simulation::endReason() const {
  const bool previewOnly = m_scene.settings.stagePlan() == StagePlan::Preview;
  // A preview that hands over to the drape is never at rest itself: the drape follows.
  if (m_atRest && (stage() == Stage::Drape || previewOnly)) return "AtRest";
  // A drape started from a preview's state (the GUI's Drape after its Preview) has solver.max_sim_time of its own: a
  // preview that ran to the limit would leave it none.
  const double start = m_drapeOwnBudget && stage() == Stage::Drape ? m_solver->previewTime : 0.0;
  if (time() - start >= m_scene.settings.number("solver.max_sim_time") - 1e-12) return "MaxSimTime";
  if (m_steps >= m_scene.settings.integer("solver.max_steps")) return "MaxSteps";
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
  const size_t restartsBefore = m_previewRestartReasons.size();
  const std::string failureBefore = m_previewFailure;
  const bool projective = !m_solver->newton;  // the constraint-based preview (or its assembly) takes this step
  if (m_solver->quasiNewtonPreview) {
    report = stepQuasiNewtonPreview();
  } else if (m_solver->preview || m_solver->assembly) {
    const bool assembling = m_solver->assembly != nullptr;
    pd::PreviewSolver& preview = assembling ? *m_solver->assembly->preview : *m_solver->preview;
    const Eigen::VectorXd& masses = assembling ? m_solver->assembly->masses : m_solver->masses;
    const Eigen::VectorXd before = preview.positions();
    const pd::PreviewReport r = preview.step();
    report.status = toStepStatus(r.status);
    report.stage = Stage::Preview;
    report.h = r.timeStep;
    report.iterations = r.iterations;
    report.cgIterations = r.pcgIterations;
    report.residual = r.residual;
    report.contacts = r.contacts;
    report.domains = r.domains;
    report.sewn = r.sewn;
    report.assembly = assembling;
    report.collisionTime = r.collisionTime;
    report.localTime = r.localTime;
    report.globalTime = r.globalTime;
    report.splits = r.splits;
    // Speeds of the step's motion, not the velocities carried on (zeroed while the preview relaxes).
    const bool stepped = r.status == pd::PreviewStatus::Converged || r.status == pd::PreviewStatus::MaxIterations;
    const Eigen::VectorXd v = stepped ? Eigen::VectorXd((preview.positions() - before) / r.timeStep)
                                      : preview.velocities();
    std::vector<double> energies(masses.size()), speeds(masses.size());
    for (Eigen::Index i = 0; i < masses.size(); ++i) {
      speeds[i] = v.segment<3>(3 * i).norm();
      energies[i] = 0.5 * masses[i] * speeds[i] * speeds[i];
    }
    report.kineticEnergy = percentile(std::move(energies), 0.99);
    // A relaxing preview moves at most g h per step whatever its forces: its rest window opens after the relaxation.
    const bool relaxing = time() < m_scene.settings.number("solver.preview.relaxation_time") - 1e-12;
    const bool settled = previewSettled(std::move(speeds), assembling || relaxing);
    const bool previewOnly = m_scene.settings.stagePlan() == StagePlan::Preview;
    // The coarse assembly has max_time from the start; the garment's own mesh has it again from where it took over
    // (or from a resumed state): it has its own settling to do.
    const double previewStart = assembling ? 0.0 : m_solver->previewOffset;
    const bool timeUp = time() - previewStart >= previewMaxTime() - 1e-12;
    report.time = time();
    ++m_steps;
    if (assembling) {
      // Sewn on the coarse mesh (or out of preview time): the garment's own mesh takes over.
      if ((r.sewn || timeUp) && stepped) finishAssembly();
    } else if (previewOnly) {
      m_atRest = settled;
      report.atRest = settled;
    } else if ((settled || timeUp) && report.status != StepStatus::Diverged) {
      startDrape(positions(), time());
    }
  } else {
    const newton::NewtonStepReport r = m_solver->newton->step();
    ++m_steps;
    m_atRest = r.atRest;
    report.status = toStepStatus(r.status);
    report.stage = Stage::Drape;
    report.time = m_solver->newtonOffset + r.time;
    report.h = r.h;
    report.iterations = r.newtonIterations;
    report.cgIterations = r.cgIterations;
    report.assemblyTime = r.hessianSeconds;
    report.gradientTime = r.gradientSeconds;
    report.linearSolveTime = r.linearSolveSeconds;
    report.hessianReused = r.hessianReused;
    report.coarseSolves = r.coarseSolves;
    report.coarseFactorizations = r.coarseFactorizations;
    report.coupledSolves = r.coupledSolves;
    report.splits = r.splits;
    report.residual = r.residual;
    report.kineticEnergy = r.kineticPercentile;
    report.atRest = r.atRest;
    report.contacts = countContacts(m_solver->contact, m_solver->newton->positions());
    report.featureContacts = countFeatureContacts(m_solver->contact, m_solver->newton->positions());
  }
  const Eigen::MatrixX3d x = positions();
  const Eigen::VectorXd stretch = triangleStretch(m_garment.rest, x, m_garment.triangles);
  report.maxStrain = stretch.size() ? stretch.maxCoeff(&report.maxStrainTriangle) : 0.0;
  if (report.stage == Stage::Preview && projective) failPreviewIfTorn(report, x);
  // The projective preview's tears start it over or give it up (failPreviewIfTorn); any other exploded state ends the
  // run Diverged with the state before the step.
  const bool restarted = m_previewRestartReasons.size() != restartsBefore || m_previewFailure != failureBefore;
  if (!restarted && report.status != StepStatus::Diverged && report.status != StepStatus::Cancelled) {
    std::string reason = explodedReason(m_garment, x, stretch, m_sceneBox, m_scene.settings.number("sim.gravity"),
                                        report.time);
    if (!reason.empty()) {
      report.status = StepStatus::Diverged;
      m_divergedReason = std::move(reason);
    }
  }
  report.wallTime = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

Snapshot Simulation::snapshot() const {
  Snapshot s = makeSnapshot(m_scene, m_garment, positions());
  if (m_solver->quasiNewtonPreview) {
    const auto& domains = m_solver->preconditioner->triangleDomain();
    s.triangleDomain = Eigen::Map<const Eigen::VectorXi>(domains.data(), static_cast<Eigen::Index>(domains.size()));
  }
  if (!m_solver->newton) {
    if (m_solver->preview) {  // the coarse assembly's domains do not colour the garment's triangles
      const auto& domains = m_solver->preview->triangleDomain();
      s.triangleDomain = Eigen::Map<const Eigen::VectorXi>(domains.data(), static_cast<Eigen::Index>(domains.size()));
    }
    Eigen::VectorXd x(3 * m_garment.vertexCount());
    for (int v = 0; v < m_garment.vertexCount(); ++v) x.segment<3>(3 * v) = s.positions.row(v).transpose();
    ContactTerms probe;
    probe.collider = m_solver->collider;
    probe.thickness = contactThickness();
    s.vertexContact = contactMask(probe, x);
  } else {
    s.vertexContact = contactMask(m_solver->contact, m_solver->newton->positions());
  }
  s.time = time();
  s.stage = m_atRest ? Stage::Done : (m_steps == 0 && !m_resumed ? Stage::Placed : stage());
  return s;
}

}  // namespace drape
