#include "drape/newton/newton_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "drape/core/percentile.h"
#include "drape/newton/body_forces.h"
#include "drape/newton/coarse_space.h"
#include "drape/newton/coupled_groups.h"
#include "drape/newton/hinge_bending.h"
#include "drape/newton/springs.h"
#include "drape/newton/strain_rate_damping.h"
#include "drape/newton/stvk_membrane.h"

namespace drape::newton {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kStandardGravity = 9.80665;  // m/s^2: the weight of a model without gravity

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

const char* toString(NewtonStatus status) {
  switch (status) {
    case NewtonStatus::Converged: return "converged";
    case NewtonStatus::MaxIterations: return "max_iterations";
    case NewtonStatus::Diverged: return "diverged";
    case NewtonStatus::Cancelled: return "cancelled";
  }
  return "unknown";
}

NewtonSolver::NewtonSolver(model::ClothModel model, NewtonSettings settings, std::vector<std::unique_ptr<Energy>> extra)
    : m_model(std::move(model)), m_settings(settings) {
  const int n = m_model.numVertices();
  if (m_model.positions.size() != 3 * n)
    throw std::invalid_argument("cloth model: positions have " + std::to_string(m_model.positions.size()) +
                                " entries, expected 3 x " + std::to_string(n) + " vertices");
  if (m_model.fabrics.empty() || (m_model.fabrics.size() != 1 && m_model.fabrics.size() != size_t(m_model.triangles.rows())))
    throw std::invalid_argument("cloth model: need one fabric or one per triangle");
  if (m_model.triangles.size() > 0 && (m_model.triangles.minCoeff() < 0 || m_model.triangles.maxCoeff() >= n))
    throw std::invalid_argument("cloth model: triangle vertex index out of range");
  m_x = m_model.positions;
  m_v = m_model.velocities.size() == 3 * n ? m_model.velocities : Eigen::VectorXd::Zero(3 * n);
  m_mass = lumpedVertexMasses(m_model);

  auto membrane = std::make_unique<StvkMembrane>(m_model);
  StvkMembrane* membraneEnergy = membrane.get();
  membrane->setExactHessian(!m_settings.projectHessians);
  std::vector<MembraneElement> elements = membrane->elements();
  m_energies.push_back(std::move(membrane));
  auto bending = std::make_unique<HingeBending>(m_model);
  HingeBending* bendingEnergy = bending.get();
  bending->setExactHessian(!m_settings.projectHessians);
  std::vector<Hinge> hinges = bending->hinges();
  if (!bending->empty()) m_energies.push_back(std::move(bending));
  model::validateStitches(m_model);
  if (!m_model.stitches.empty() || !m_model.edgeStitches.empty())
    m_energies.push_back(
        std::make_unique<StitchSprings>(m_model.stitches, m_settings.stitchStiffness, m_model.edgeStitches));
  if (!m_model.pinned.empty()) {
    std::vector<Eigen::Vector3d> targets = m_model.pinTargets;
    if (targets.empty())
      for (int v : m_model.pinned) targets.push_back(m_x.segment<3>(3 * v));
    m_energies.push_back(std::make_unique<PinSprings>(m_model.pinned, targets, m_settings.pinStiffness,
                                                      m_model.pinTrajectory, m_model.startTime));
  }
  if (m_model.gravity.squaredNorm() > 0.0) m_energies.push_back(std::make_unique<Gravity>(m_mass, m_model.gravity));
  if (m_settings.alpha > 0.0) m_energies.push_back(std::make_unique<AirDrag>(m_mass, m_settings.alpha));
  // The dissipations share the membrane's triangles and the bending's hinges: folded into their Hessian passes.
  if (m_settings.betaStretch > 0.0) {
    auto stretch = std::make_unique<MembraneDissipation>(elements, m_settings.betaStretch);
    membraneEnergy->foldDissipation(stretch.get());
    membraneEnergy->setRecordDeformationGradients(true);
    stretch->setStartSource(membraneEnergy);
    stretch->setFolded(true);
    m_energies.push_back(std::move(stretch));
  }
  if (m_settings.betaBend > 0.0 && !hinges.empty()) {
    auto bend = std::make_unique<BendingDissipation>(hinges, m_settings.betaBend);
    bendingEnergy->foldDissipation(bend.get());
    bendingEnergy->setRecordAngleGradients(true);
    bend->setGradientSource(bendingEnergy);
    bend->setFolded(true);
    m_energies.push_back(std::move(bend));
  }
  m_elasticCount = m_energies.size();
  for (auto& e : extra) m_energies.push_back(std::move(e));

  std::vector<std::pair<int, int>> couplings;
  for (const auto& e : m_energies) e->addCouplings(couplings);
  m_matrix.build(n, couplings, m_settings.reorderDofs);
  if (m_settings.coarseAggregate > 1 && m_settings.linear.fusedKernels)
    m_coarse = std::make_unique<CoarseSpace>(m_matrix, m_settings.coarseAggregate);
  m_coupled = std::make_unique<CoupledGroups>();
  m_useCoupled = m_settings.coupledFromIterations <= 0;
  m_useCoarse = m_settings.coarseFromIterations <= 0;
  m_h = m_settings.relaxation ? m_settings.hMax / m_settings.relaxationStepDivisor : m_settings.hMax;
  if (m_settings.startStep > 0.0) m_h = std::min(m_h, m_settings.startStep);
}

NewtonSolver::~NewtonSolver() = default;

AssemblyOptions NewtonSolver::assemblyOptions() const {
  AssemblyOptions o;
  o.closedFormBending = m_settings.closedFormBending;
  o.cachedBlockMap = m_settings.cachedBlockMap;
  o.parallel = m_settings.parallelAssembly;
  o.foldDissipation = m_settings.foldDissipation;
  o.batchedGradients = m_settings.batchedGradients;
  return o;
}

void NewtonSolver::setDrag(int vertex, const Eigen::Vector3d& target) {
  if (vertex >= m_model.numVertices()) throw std::invalid_argument("drag: vertex index out of range");
  if (!m_drag) {
    if (vertex < 0) return;
    auto drag = std::make_unique<PinSprings>(std::vector<int>{}, std::vector<Eigen::Vector3d>{}, m_settings.pinStiffness,
                                             PinSprings::Trajectory{}, 0.0, "drag");
    m_drag = drag.get();
    m_energies.push_back(std::move(drag));
  }
  if (vertex < 0)
    m_drag->setPins({}, {});
  else
    m_drag->setPins({vertex}, {target});
}

void NewtonSolver::setQuasiNewton(std::shared_ptr<model::StepPreconditioner> preconditioner, QuasiNewtonSettings settings) {
  m_quasiNewton = std::move(preconditioner);
  m_qnSettings = settings;
  // The Newton matrix and the last step's Newton data do not carry across the switch.
  m_matrixReady = false;
  m_elasticHessianH = 0.0;
  m_pcgCache.valid = false;
  m_coarseStale = true;
  m_coupledStale = true;
}

std::vector<std::string> NewtonSolver::energyNames() const {
  std::vector<std::string> names;
  for (const auto& e : m_energies) names.emplace_back(e->name());
  return names;
}

double NewtonSolver::totalEnergy(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (const auto& e : m_energies) sum += e->value(x);
  return sum;
}

double NewtonSolver::kineticEnergyPercentile() const {
  std::vector<double> ke(m_mass.size());
  for (size_t i = 0; i < ke.size(); ++i) ke[i] = 0.5 * m_mass(i) * m_v.segment<3>(3 * i).squaredNorm();
  return percentile(std::move(ke), m_settings.restPercentile);
}

double NewtonSolver::speedPercentile() const {
  std::vector<double> speed(m_mass.size());
  for (size_t i = 0; i < speed.size(); ++i) speed[i] = m_mass(i) > 0.0 ? m_v.segment<3>(3 * i).norm() : 0.0;
  return percentile(std::move(speed), m_settings.restPercentile);
}

bool NewtonSolver::residualBelowRest(const Eigen::VectorXd& b) const {
  if (!m_nearRest) return true;
  // The velocity error |b_i| / m_i of vertex i, and, in a step that starts as slow as the early stop asks, the
  // unbalanced force the residual leaves, |b_i| / h, as a fraction of the vertex's weight: a residual below tau_n can
  // still leave a force that keeps the garment out of equilibrium (NewtonSettings::restForce).
  const double weight = m_model.gravity.norm() > 0.0 ? m_model.gravity.norm() : kStandardGravity;
  std::vector<double> error(m_mass.size());
  double forceSquares = 0.0;
  int count = 0;
  for (size_t i = 0; i < error.size(); ++i) {
    if (m_mass(i) <= 0.0) {
      error[i] = 0.0;
      continue;
    }
    const double r = b.segment<3>(3 * i).norm();
    error[i] = r / m_mass(i);
    forceSquares += std::pow(r / (m_h * m_mass(i) * weight), 2);
    ++count;
  }
  const double forceRms = count > 0 ? std::sqrt(forceSquares / count) : 0.0;
  return percentile(std::move(error), m_settings.restPercentile) < m_settings.restSpeed &&
         (!m_slowStart || forceRms <= m_settings.restForce);
}

void NewtonSolver::measureEquilibrium(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                      NewtonStepReport& report) const {
  const double g = m_model.gravity.norm() > 0.0 ? m_model.gravity.norm() : kStandardGravity;
  const bool haveResidual = m_lastResidual.size() == x.size();
  double largest = 0.0, sumSquares = 0.0, displacement = 0.0;
  int count = 0;
  for (int i = 0; i < m_mass.size(); ++i) {
    displacement = std::max(displacement, (x.segment<3>(3 * i) - m_x.segment<3>(3 * i)).norm());
    if (m_mass(i) <= 0.0) continue;
    Eigen::Vector3d f = m_mass(i) * (v.segment<3>(3 * i) - m_v.segment<3>(3 * i));
    if (haveResidual) f += m_lastResidual.segment<3>(3 * i);
    const double fraction = f.norm() / (m_h * m_mass(i) * g);
    largest = std::max(largest, fraction);
    sumSquares += fraction * fraction;
    ++count;
  }
  report.forceMax = largest;
  report.forceRms = count > 0 ? std::sqrt(sumSquares / count) : 0.0;
  report.displacementMax = displacement;
}

// Right-hand side of eq. 4: b = M (v_n - v) - h dE/dx(x); its norm is the Newton residual.
void NewtonSolver::residual(const Eigen::VectorXd& x, const Eigen::VectorXd& v, double h, Eigen::VectorXd& b) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  for (const auto& e : m_energies) e->addGradient(x, g);
  momentumResidual(g, v, h, b);
}

void NewtonSolver::momentumResidual(const Eigen::VectorXd& g, const Eigen::VectorXd& v, double h,
                                    Eigen::VectorXd& b) const {
  b = -h * g;
  for (int i = 0; i < m_mass.size(); ++i) b.segment<3>(3 * i) += m_mass(i) * (m_v.segment<3>(3 * i) - v.segment<3>(3 * i));
}

bool NewtonSolver::assembleFirstIteration(const Eigen::VectorXd& x, double h, bool atStepStart, Eigen::VectorXd& g,
                                          int& recordedGradients) {
  const bool inPlace = m_matrixReady && !hasFreshTerms();
  const bool reuse = m_settings.hessianReuseSteps > 0 && m_elasticHessianH == h &&
                     m_elasticHessianAge < m_settings.hessianReuseSteps && m_lastNewtonIterations == 1 &&
                     (inPlace || (m_elasticHessianCopied &&
                                  m_elasticHessian.size() == size_t(m_matrix.staticBlockCount())));
  // At the step's start (relaxation: x = x_n, zero velocities) an energy may hand back the gradient its last
  // pass recorded there (the accepted state of the last step).
  auto recorded = [&](size_t k) {
    const bool used = atStepStart && m_energies[k]->addRecordedStepStartGradient(x, g);
    recordedGradients += used;
    return used;
  };
  if (!reuse || !inPlace) m_matrixReady = false;
  if (reuse) {
    if (!inPlace) m_matrix.setStaticValues(m_elasticHessian);
    for (size_t k = 0; k < m_elasticCount; ++k)
      if (!recorded(k)) m_energies[k]->addGuessGradient(x, g);
    ++m_elasticHessianAge;
  } else {
    m_coarseStale = m_coupledStale = true;
    m_matrix.setZero();
    for (size_t k = 0; k < m_elasticCount; ++k) {
      if (recorded(k))
        m_energies[k]->addHessian(x, m_matrix);
      else
        m_energies[k]->addGradientAndHessian(x, g, m_matrix);
    }
    saveElasticHessian(h);
  }
  for (size_t k = m_elasticCount; k < m_energies.size(); ++k)
    m_energies[k]->addPredictionGradientAndHessian(x, g, m_matrix);
  return reuse;
}

void NewtonSolver::assembleHessian(const Eigen::VectorXd& x, double h) {
  m_coupledStale = true;
  if (!m_settings.coarseLagged) m_coarseStale = true;
  m_matrixReady = false;
  m_matrix.setZero();
  for (size_t k = 0; k < m_elasticCount; ++k) m_energies[k]->addHessian(x, m_matrix);
  saveElasticHessian(h);
  for (size_t k = m_elasticCount; k < m_energies.size(); ++k) m_energies[k]->addHessian(x, m_matrix);
}

void NewtonSolver::saveElasticHessian(double h) {
  if (m_settings.hessianReuseSteps <= 0) return;
  m_elasticHessianCopied = hasFreshTerms();
  if (m_elasticHessianCopied) m_elasticHessian = m_matrix.blocks();
  m_elasticHessianH = h;
  m_elasticHessianAge = 0;
}

bool NewtonSolver::hasFreshTerms() const {
  return m_energies.size() > m_elasticCount || !m_matrix.dynamicEntries().empty();
}

NewtonStatus NewtonSolver::attempt(double h, double scale, Eigen::VectorXd& x, Eigen::VectorXd& v,
                                   NewtonStepReport& report) {
  if (m_quasiNewton) return attemptQuasiNewton(h, scale, x, v, report);
  StepContext ctx{&m_x, &m_v, h, m_time, scale, assemblyOptions()};
  auto t0 = Clock::now();
  for (auto& e : m_energies) e->beginStep(ctx);
  report.contactQuerySeconds += secondsSince(t0);
  // A relaxation step (zero v_n) may start from the last step's motion (NewtonSettings::relaxationGuess).
  const bool guess = m_settings.relaxationGuess && report.relaxing && m_lastDv.size() == m_v.size() && m_lastDvH > 0.0;
  v = guess ? Eigen::VectorXd((h / m_lastDvH) * m_lastDv) : m_v;
  x = m_x + h * v;
  // b is the member itself: whichever state the attempt ends in, m_lastResidual is its residual.
  Eigen::VectorXd& b = m_lastResidual;
  Eigen::VectorXd dv, vls, xls, bls;
  const double invH2 = 1.0 / (h * h);
  // The first iteration needs the gradient and the Hessian at the same x: one pass over the stencils.
  t0 = Clock::now();
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  const bool atStepStart = !guess && m_settings.stepStartGradients && m_v.isZero(0.0);
  report.hessianReused = assembleFirstIteration(x, h, atStepStart, g, report.recordedGradients);
  momentumResidual(g, v, h, b);
  report.hessianSeconds += secondsSince(t0);
  if (!b.allFinite()) return NewtonStatus::Diverged;
  double rn = b.norm();
  report.residual = rn;
  report.residualHistory.assign(1, rn);
  // As Algorithm 1, at least one Newton iteration runs before the tolerance test.
  for (int it = 0; it < m_settings.maxNewtonIterations; ++it) {
    if (m_cancel.load()) return NewtonStatus::Cancelled;
    // (M + h^2 H) dv = b, solved as (M / h^2 + H) dv = b / h^2.
    t0 = Clock::now();
    if (it > 0) assembleHessian(x, h);
    if (!m_matrixReady) {
      for (int i = 0; i < m_mass.size(); ++i) m_matrix.diagonalBlock(i).diagonal().array() += m_mass(i) * invH2;
      m_pcgCache.valid = false;
    }
    // Contact, friction and the drag spring add fresh blocks in every iteration; without them the coupled groups'
    // inverses live as long as the elastic Hessian (hessianReuseSteps), and so does the matrix. The lagged coarse
    // factor lives that long with them too (NewtonSettings::coarseLagged).
    const bool useCoarse = m_coarse && m_useCoarse;
    const bool useGroups = m_settings.coupledThreshold > 0.0 && m_settings.linear.fusedKernels && m_useCoupled;
    const bool freshTerms = hasFreshTerms();
    m_matrixReady = !freshTerms && m_settings.hessianReuseSteps > 0;
    if (useCoarse && (m_coarseStale || m_coarseH != h || (freshTerms && !m_settings.coarseLagged))) {
      m_coarse->factorize(m_matrix);
      ++report.coarseFactorizations;
      m_coarseStale = false;
      m_coarseH = h;
    }
    // The groups are found once per step size (a stitch stays a stitch, and scanning every block for them costs more
    // than a short step's solve saves); their inverses follow the matrix.
    if (useGroups && m_coupledH != h) {
      *m_coupled = CoupledGroups(m_matrix, m_settings.coupledThreshold);
      m_coupledH = h;
      m_coupledStale = false;
    } else if (useGroups && (m_coupledStale || freshTerms)) {
      m_coupled->refresh(m_matrix);
      m_coupledStale = false;
    }
    report.hessianSeconds += secondsSince(t0);
    t0 = Clock::now();
    // PCG initial guess (used when linear.warmStart): the first Newton system of a step is close to the last
    // step's velocity change (scaled to this h); later iterations solve for corrections and start from 0, and so
    // does a relaxation step whose first iterate already is that change.
    if (it == 0 && !guess && m_lastDv.size() == v.size() && m_lastDvH > 0.0)
      dv = (h / m_lastDvH) * m_lastDv;
    else
      dv.resize(0);
    LinearSolveOptions linear = m_settings.linear;
    linear.coarse = useCoarse ? m_coarse.get() : nullptr;
    linear.coupled = useGroups && !m_coupled->empty() ? m_coupled.get() : nullptr;
    linear.trueResidual = false;
    linear.cache = m_matrixReady ? &m_pcgCache : nullptr;
    if (m_settings.cgForcing > 0.0 && rn > 0.0)
      linear.tolerance = std::max(linear.tolerance, std::min(0.5, m_settings.cgForcing * m_settings.tauNewton / rn));

    LinearSolveResult ls = solveLinear(m_matrix, b * invH2, dv, linear);
    report.linearSolveSeconds += secondsSince(t0);
    ++report.newtonIterations;
    report.cgIterations += ls.iterations;
    report.coarseSolves += linear.coarse != nullptr;
    report.coupledSolves += linear.coupled != nullptr;
    // The coarse level and the coupled groups pay for themselves only on solves that need many PCG iterations
    // (stiff fabric, fine mesh, long steps).
    const int from = m_settings.coarseFromIterations;
    if (!useCoarse && ls.iterations >= from)
      m_useCoarse = true;
    else if (useCoarse && ls.iterations < from / 4)
      m_useCoarse = false;
    const int coupledFrom = m_settings.coupledFromIterations;
    if (!m_useCoupled && ls.iterations >= coupledFrom)
      m_useCoupled = true;
    else if (useGroups && ls.iterations < coupledFrom / 2)
      m_useCoupled = false;
    if (!ls.ok) return NewtonStatus::Diverged;
    // Backtracking line search halving the step until the residual decreases (Algorithm 1, lines 15-27).
    bool accepted = false;
    bool fullStep = false;
    double f = 1.0;
    for (int k = 0; k < m_settings.maxLineSearchIterations && !accepted; ++k, f *= 0.5) {
      vls = v + f * dv;
      xls = m_x + h * vls;
      t0 = Clock::now();
      residual(xls, vls, h, bls);
      report.gradientSeconds += secondsSince(t0);
      double r = bls.norm();
      if (std::isfinite(r) && r < rn) {
        accepted = true;
        fullStep = k == 0;
        rn = r;
        v.swap(vls);
        x.swap(xls);
        b.swap(bls);
      }
    }
    report.residual = rn;
    if (accepted) report.residualHistory.push_back(rn);
    // A reused Hessian counts only when its full Newton step was taken: after backtracking (the old matrix no
    // longer fits) the step iterates on with a fresh one, even below tau_n (near rest tau_n alone would accept
    // velocities that keep the garment from settling).
    if (it == 0 && report.hessianReused && !fullStep) continue;
    if (!accepted) return rn < m_settings.tauNewton ? NewtonStatus::Converged : NewtonStatus::Diverged;
    const bool lastIteration = it + 1 == m_settings.maxNewtonIterations;
    if (rn < m_settings.tauNewton && (lastIteration || residualBelowRest(b))) return NewtonStatus::Converged;
  }
  return NewtonStatus::MaxIterations;
}

NewtonStepReport NewtonSolver::step() {
  NewtonStepReport report;
  report.energies = energyNames();
  report.time = m_time;
  const NewtonSettings& s = m_settings;
  const bool relaxing = s.relaxation && m_time < s.relaxationTime;
  report.relaxing = relaxing;
  const double hCap = relaxing && s.relaxationHoldStep ? s.hMax / s.relaxationStepDivisor : s.hMax;
  m_h = std::min(m_h, hCap);
  const double scale =
      relaxing ? s.relaxationStartScale + (1.0 - s.relaxationStartScale) * (m_time / s.relaxationTime) : 1.0;
  // A relaxation step ends with zero velocities, so the next one starts where this one's last gradient pass ran
  // (unless the relaxation guess starts it elsewhere).
  for (size_t k = 0; k < m_elasticCount; ++k)
    m_energies[k]->setRecordStepStartGradient(relaxing && s.stepStartGradients && !s.relaxationGuess &&
                                              !m_quasiNewton);
  const double speed = speedPercentile();
  m_nearRest = s.restAwareConvergence && !relaxing && speed < s.restAwareFactor * s.restSpeed;
  m_slowStart = m_nearRest && speed < s.restSpeed;
  Eigen::VectorXd x, v;
  NewtonStatus keptStatus = NewtonStatus::Converged;
  while (true) {
    if (m_cancel.load()) {
      report.status = NewtonStatus::Cancelled;
      return report;
    }
    NewtonStatus st = attempt(m_h, scale, x, v, report);
    if (st == NewtonStatus::Cancelled) {
      report.status = st;
      return report;  // state untouched: the step restarts from the last good state
    }
    // The quasi-Newton preview keeps a step its iterations left above tau_n.
    const bool kept = st == NewtonStatus::Converged || (m_quasiNewton && st == NewtonStatus::MaxIterations);
    if (kept && x.allFinite() && v.allFinite()) {
      keptStatus = st;
      break;
    }
    // Time splitting (3.1.3): restore (state was never overwritten) and retry with a smaller step.
    m_goodSteps = 0;
    ++report.splits;
    if (m_h * s.omega < s.hMin) {
      // Not even the smallest step converges (diverging, or the residual stalls above tau_n): Diverged, with the
      // last good state kept. Reporting MaxIterations here let callers retry the same failing step forever.
      report.status = NewtonStatus::Diverged;
      report.h = m_h;
      m_h = hCap;
      report.kineticPercentile = kineticEnergyPercentile();
      return report;
    }
    m_h *= s.omega;
  }
  measureEquilibrium(x, v, report);
  m_x = x;
  m_lastNewtonIterations = static_cast<int>(report.residualHistory.size()) - 1;
  m_lastDv = v - m_v;
  m_lastDvH = m_h;
  m_v = relaxing ? Eigen::VectorXd::Zero(v.size()) : v;  // relaxation zeroes velocities after every step (5.2)
  report.h = m_h;
  m_time += m_h;
  report.time = m_time;
  report.status = keptStatus;
  if (++m_goodSteps >= s.growAfterSteps && m_h < hCap) {
    m_h = std::min(hCap, m_h / s.omega);
    m_goodSteps = 0;
  }
  report.kineticPercentile = kineticEnergyPercentile();
  report.speedPercentile = speedPercentile();
  if (relaxing || report.speedPercentile >= s.restSpeed)
    m_restSince = -1.0;
  else if (m_restSince < 0.0)
    m_restSince = m_time - m_h;
  report.atRest = atRest();
  return report;
}

}  // namespace drape::newton
