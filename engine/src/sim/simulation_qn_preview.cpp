// The quasi-Newton preview of a Simulation (solver.preview.method quasi_newton): the Newton drape's solver, with the
// drape's energies, solves each step by L-BFGS preconditioned by the PD-DD system at the preview's longer step; the
// hand-over switches the same solver to Newton, so the drape goes on from the preview's positions, velocities and
// time with nothing to undo.

#include "drape/sim/simulation.h"
#include "sim/cloth_model_builder.h"
#include "sim/simulation_solver.h"

namespace drape {
namespace {

constexpr double kRelaxationStepDivisor = 4.0;

}  // namespace

bool Simulation::quasiNewtonMethod() const {
  return m_scene.settings.text("solver.preview.method") == "quasi_newton";
}

void Simulation::startQuasiNewtonPreview(const ResumeState* from) {
  m_solver->assembly.reset();
  m_solver->preview.reset();
  m_solver->newton.reset();
  m_solver->previewPositions.resize(0, 3);
  m_solver->previewTime = 0.0;
  m_atRest = false;
  m_restSince = -1.0;
  const Settings& s = m_scene.settings;
  model::ClothModel model = m_solver->model;
  newton::NewtonSettings settings = newtonSettingsFrom(m_scene);
  settings.hMax = s.number("solver.preview.qn_time_step");
  // The relaxation (velocities zeroed, stiffness ramped) as the drape's, its first steps a quarter of the preview's
  // (growing by the time-splitting rule): the seams close with fewer overstretched triangles than from the full step
  // or the drape's sixteenth, and faster (docs/BENCHMARKS.md, "A preview on the drape's model").
  settings.relaxationStepDivisor = kRelaxationStepDivisor;
  double start = 0.0;
  if (from) {  // a state at rest or a running preview's: no quasi-static start again
    const int n = m_garment.vertexCount();
    model.velocities.resize(3 * n);
    for (int v = 0; v < n; ++v) {
      model.positions.segment<3>(3 * v) = from->positions.row(v).transpose();
      model.velocities.segment<3>(3 * v) = from->velocities.row(v).transpose();
    }
    start = from->time;
    settings.relaxation = false;
    settings.startStep = settings.hMax;
  }
  model.startTime = start;
  m_solver->newtonOffset = start;
  m_solver->previewOffset = start;
  m_solver->contact = makeContactTerms(m_scene, m_garment, m_solver->collider);
  const pd::GlobalSolverKind kind = m_scene.implementation.monolithicGlobalSolve
                                        ? pd::GlobalSolverKind::Monolithic
                                        : pd::GlobalSolverKind::DomainDecomposed;
  m_solver->preconditioner = std::make_shared<pd::PdPreconditioner>(
      model, settings.stitchStiffness, settings.pinStiffness, settings.alpha, settings.betaStretch, settings.betaBend,
      s.integer("solver.preview.domains"), kind);
  m_solver->newton =
      std::make_unique<newton::NewtonSolver>(std::move(model), settings, std::move(m_solver->contact.energies));
  newton::QuasiNewtonSettings qn;
  qn.maxIterations = s.integer("solver.preview.qn_iterations");
  m_solver->newton->setQuasiNewton(m_solver->preconditioner, qn);
  m_solver->quasiNewtonPreview = true;
  if (m_dragVertex >= 0) m_solver->newton->setDrag(m_dragVertex, m_dragTarget);
}

void Simulation::handOverToDrape() {
  m_solver->previewPositions = positions();
  m_solver->previewTime = time();
  newton::NewtonSolver& solver = *m_solver->newton;
  solver.setQuasiNewton(nullptr);
  const newton::NewtonSettings drape = newtonSettingsFrom(m_scene);
  solver.settings().hMax = drape.hMax * m_scene.settings.number("solver.newton.h_max_factor_after_preview");
  // Newton starts at its own h_max and grows from there, as after the projective preview: at the preview's step the
  // first Newton steps of a garment still moving can fail to converge and split down to 0.1 ms.
  solver.restartStepSize(drape.hMax);
  m_solver->quasiNewtonPreview = false;
  m_atRest = false;
}

StepReport Simulation::stepQuasiNewtonPreview() {
  newton::NewtonSolver& solver = *m_solver->newton;
  const Eigen::VectorXd before = solver.positions();
  const newton::NewtonStepReport r = solver.step();
  ++m_steps;
  StepReport report;
  switch (r.status) {
    case newton::NewtonStatus::Converged: report.status = StepStatus::Converged; break;
    case newton::NewtonStatus::MaxIterations: report.status = StepStatus::MaxIterations; break;
    case newton::NewtonStatus::Diverged: report.status = StepStatus::Diverged; break;
    case newton::NewtonStatus::Cancelled: report.status = StepStatus::Cancelled; break;
  }
  report.stage = Stage::Preview;
  report.quasiNewton = true;
  report.time = time();
  report.h = r.h;
  report.iterations = r.newtonIterations;
  report.lineSearchEvaluations = r.lineSearchEvaluations;
  report.domains = m_solver->preconditioner->domainCount();
  report.splits = r.splits;
  report.residual = r.residual;
  report.kineticEnergy = r.kineticPercentile;
  report.assemblyTime = r.hessianSeconds;
  report.gradientTime = r.gradientSeconds;
  report.linearSolveTime = r.linearSolveSeconds;
  report.contacts = countContacts(m_solver->contact, solver.positions());
  const bool stepped = r.status == newton::NewtonStatus::Converged || r.status == newton::NewtonStatus::MaxIterations;
  std::vector<double> speeds(static_cast<size_t>(m_garment.vertexCount()), 0.0);
  if (stepped && r.h > 0.0)
    for (size_t i = 0; i < speeds.size(); ++i)
      speeds[i] = (solver.positions().segment<3>(3 * i) - before.segment<3>(3 * i)).norm() / r.h;
  const bool settled = previewSettled(std::move(speeds), r.relaxing || !stepped);
  const bool previewOnly = m_scene.settings.stagePlan() == StagePlan::Preview;
  const bool timeUp = time() - m_solver->previewOffset >= m_scene.settings.number("solver.preview.max_time") - 1e-12;
  if (previewOnly) {  // the drape's own early stop: the same model comes to rest by the same test
    m_atRest = solver.atRest();
    report.atRest = m_atRest;
  } else if (settled || timeUp || r.status == newton::NewtonStatus::Diverged) {
    handOverToDrape();
  }
  return report;
}

}  // namespace drape
