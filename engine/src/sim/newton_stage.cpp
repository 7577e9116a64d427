#include "sim/newton_stage.h"

#include <algorithm>

#include "drape/pd/pd_preconditioner.h"

namespace drape {
namespace {

StepStatus statusOf(newton::NewtonStatus s) {
  switch (s) {
    case newton::NewtonStatus::Converged: return StepStatus::Converged;
    case newton::NewtonStatus::MaxIterations: return StepStatus::MaxIterations;
    case newton::NewtonStatus::Diverged: return StepStatus::Diverged;
    case newton::NewtonStatus::Cancelled: return StepStatus::Cancelled;
  }
  return StepStatus::Diverged;
}

// The preview's relaxation starts at a quarter of its step (growing by the time-splitting rule): the seams close
// with fewer overstretched triangles than from the full step or the drape's sixteenth, and sooner (docs/BENCHMARKS.md,
// "A preview on the drape's model").
constexpr double kPreviewRelaxationDivisor = 4.0;

model::ClothModel startingAt(model::ClothModel model, const StageStart& start) {
  if (start.positions.size() == model.positions.size()) model.positions = start.positions;
  if (start.velocities.size() == model.positions.size())
    model.velocities = start.velocities;
  else
    model.velocities = Eigen::VectorXd::Zero(model.positions.size());
  model.startTime = start.time;
  return model;
}

}  // namespace

NewtonStage::NewtonStage(Stage stage, model::ClothModel model, const newton::NewtonSettings& settings,
                         ContactTerms contact, QuasiNewtonStrategy strategy)
    : m_stage(stage), m_offset(model.startTime), m_contact(std::move(contact)), m_strategy(std::move(strategy)) {
  m_solver = std::make_unique<newton::NewtonSolver>(std::move(model), settings, std::move(m_contact.energies));
  m_contact.energies.clear();
  if (m_strategy.preconditioner) m_solver->setQuasiNewton(m_strategy.preconditioner, m_strategy.settings);
}

StepReport NewtonStage::step() {
  const newton::NewtonStepReport r = m_solver->step();
  StepReport report;
  report.status = statusOf(r.status);
  report.stage = m_stage;
  report.time = time();
  report.h = r.h;
  report.iterations = r.newtonIterations;
  report.cgIterations = r.cgIterations;
  report.lineSearchEvaluations = r.lineSearchEvaluations;
  report.quasiNewton = r.quasiNewton;
  report.domains = m_strategy.domains;
  report.assemblyTime = r.hessianSeconds;
  report.gradientTime = r.gradientSeconds;
  report.linearSolveTime = r.linearSolveSeconds;
  report.contactQueryTime = r.contactQuerySeconds;
  report.forceMax = r.forceMax;
  report.forceRms = r.forceRms;
  report.displacementMax = r.displacementMax;
  report.hessianReused = r.hessianReused;
  report.coarseSolves = r.coarseSolves;
  report.coarseFactorizations = r.coarseFactorizations;
  report.coupledSolves = r.coupledSolves;
  report.splits = r.splits;
  report.residual = r.residual;
  report.kineticEnergy = r.kineticPercentile;
  report.relaxing = r.relaxing;
  report.atRest = r.atRest;
  report.contacts = countContacts(m_contact, m_solver->positions());
  report.featureContacts = countFeatureContacts(m_contact, m_solver->positions());
  return report;
}

Eigen::VectorXi NewtonStage::contactMask() const {
  return drape::contactMask(m_contact, m_solver->positions());
}

Eigen::VectorXi NewtonStage::triangleDomains() const {
  const std::vector<int>& d = m_strategy.triangleDomain;
  return Eigen::Map<const Eigen::VectorXi>(d.data(), static_cast<Eigen::Index>(d.size()));
}

std::unique_ptr<StageSolver> makePreviewStage(const model::ClothModel& model, const SimulationSettings& settings,
                                              ContactTerms contact, const StageStart& start, bool placed) {
  const PreviewStageSettings& p = settings.preview;
  newton::NewtonSettings n = settings.drape.newton;
  n.hMax = p.timeStep;
  n.relaxationStepDivisor = kPreviewRelaxationDivisor;
  if (!placed) {  // a state at rest or a running preview's: no relaxation again
    n.relaxation = false;
    n.startStep = n.hMax;
  }
  model::ClothModel m = startingAt(model, start);
  auto preconditioner = std::make_shared<pd::PdPreconditioner>(
      m, n.stitchStiffness, n.pinStiffness, n.alpha, n.betaStretch, n.betaBend, p.domains,
      p.monolithic ? pd::GlobalSolverKind::Monolithic : pd::GlobalSolverKind::DomainDecomposed);
  QuasiNewtonStrategy strategy;
  strategy.settings.maxIterations = p.iterations;
  strategy.domains = preconditioner->domainCount();
  strategy.triangleDomain = preconditioner->triangleDomain();
  strategy.preconditioner = std::move(preconditioner);
  return std::make_unique<NewtonStage>(Stage::Preview, std::move(m), n, std::move(contact), std::move(strategy));
}

std::unique_ptr<StageSolver> makeSettleStage(const model::ClothModel& model, const SimulationSettings& settings,
                                             ContactTerms contact, const StageStart& start) {
  newton::NewtonSettings n = settings.drape.newton;
  n.relaxation = false;
  n.startStep = n.hMax;
  n.hMax = std::max(n.hMax, settings.preview.timeStep);
  return std::make_unique<NewtonStage>(Stage::Preview, startingAt(model, start), n, std::move(contact));
}

std::unique_ptr<StageSolver> makeDrapeStage(const model::ClothModel& model, const SimulationSettings& settings,
                                            ContactTerms contact, const StageStart& start, bool placed) {
  newton::NewtonSettings n = settings.drape.newton;
  // The relaxation settles a placed garment (seams apart, pre-stretch); a preview has already done that. Its steps
  // may be longer: it settles a garment already near rest, whose result they barely move (docs/BENCHMARKS.md,
  // "Findings worth keeping"). They start at h_max and grow: at a preview's step the first Newton steps of a garment
  // still moving can fail to converge and split many times.
  if (!placed) {
    n.relaxation = settings.drape.relaxationAfterPreview;
    n.startStep = n.hMax;
    n.hMax *= settings.drape.hMaxFactorAfterPreview;
  }
  return std::make_unique<NewtonStage>(Stage::Drape, startingAt(model, start), n, std::move(contact));
}

}  // namespace drape
