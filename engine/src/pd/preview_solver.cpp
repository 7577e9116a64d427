#include "drape/pd/preview_solver.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <functional>
#include <stdexcept>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "drape/collision/avatar_collider.h"
#include "drape/pd/anderson.h"
#include "drape/pd/avatar_collision.h"
#include "drape/pd/cloth_collision.h"
#include "drape/pd/contact_factor.h"
#include "drape/pd/contact_solve.h"
#include "drape/pd/dd_solver.h"
#include "drape/pd/domain_partition.h"
#include "drape/pd/local_step.h"
#include "drape/pd/pd_system.h"

namespace drape::pd {
namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

Eigen::MatrixX3d asRows(const Eigen::VectorXd& flat, int nv) {
  Eigen::MatrixX3d m(nv, 3);
  for (int v = 0; v < nv; ++v) m.row(v) = flat.segment<3>(3 * v).transpose();
  return m;
}

void toFlat(const Eigen::MatrixX3d& m, Eigen::VectorXd& flat) {
  flat.resize(3 * m.rows());
  for (int v = 0; v < m.rows(); ++v) flat.segment<3>(3 * v) = m.row(v).transpose();
}

// Adds the iterations and times of `earlier` (attempts redone at a smaller step) to `report`.
void addWork(const PreviewReport& earlier, PreviewReport& report) {
  report.iterations += earlier.iterations;
  report.sdIterations += earlier.sdIterations;
  report.pcgIterations += earlier.pcgIterations;
  report.contactChurn += earlier.contactChurn;
  report.collisionTime += earlier.collisionTime;
  report.contactSolveTime += earlier.contactSolveTime;
  report.localTime += earlier.localTime;
  report.globalTime += earlier.globalTime;
}

// Largest distance between the two sides of a stitch (vertex pairs and vertex-to-edge points), metres.
double largestStitchGap(const model::ClothModel& model, const Eigen::MatrixX3d& x) {
  double gap = 0.0;
  for (const auto& [a, b] : model.stitches) gap = std::max(gap, (x.row(a) - x.row(b)).norm());
  for (const model::EdgeStitch& e : model.edgeStitches)
    gap = std::max(gap, (x.row(e.vertex) - (1.0 - e.t) * x.row(e.a) - e.t * x.row(e.b)).norm());
  return gap;
}

}  // namespace

const char* toString(PreviewStatus status) {
  switch (status) {
    case PreviewStatus::Converged: return "converged";
    case PreviewStatus::MaxIterations: return "max_iterations";
    case PreviewStatus::Diverged: return "diverged";
    case PreviewStatus::Cancelled: return "cancelled";
  }
  return "unknown";
}

struct PreviewSolver::Impl {
  PreviewSettings settings;
  std::shared_ptr<const collision::AvatarCollider> collider;
  std::unique_ptr<tbb::task_arena> arena;
  // The system, its global solver and local step for the time step settings.timeStep / 2^k (level k), built on
  // first use from the kept model: K = M / h^2 + sum w A^T A changes with h.
  struct Level {
    std::unique_ptr<PdSystem> system;
    std::unique_ptr<GlobalSolver> global;
    std::unique_ptr<LocalStep> local;
    std::unique_ptr<ContactFactor> contactFactor;  // settings.contactSolve == Factor, built on first contact
  };
  model::ClothModel model;
  std::vector<Level> levels;
  int level = 0;
  int convergedInARow = 0;  // steps converged at the current level since it was entered
  bool sewn = false;        // settings.sewnGap held for settings.sewnTime (latched)
  double closedSince = -1.0;  // scene time since which every stitch gap is below settings.sewnGap; -1: not now
  PdSystem* system = nullptr;  // of the current level
  GlobalSolver* global = nullptr;
  LocalStep* local = nullptr;
  // The collision-aware correction of xFree (the collision-free solve) for `contacts`, by settings.contactSolve.
  // xFree: on entry K^-1 b (the collision-free solve of right-hand side b), on exit the solution with contacts.
  ContactSolveStats solveContacts(const ContactSet& contacts, const Eigen::MatrixX3d& b, Eigen::MatrixX3d& xFree);
  std::vector<int> triangleDomain;
  int domains = 1;
  Eigen::MatrixX3d x, v;  // |V| x 3
  Eigen::VectorXd flatX, flatV;
  std::vector<StrainTarget> targets;
  std::atomic<bool> cancel{false};
  double time = 0.0;
  // Moving pins: trajectory of model pin p at scene time startTime + time; pinSource[k] = p of pinned row k.
  std::function<Eigen::Vector3d(int, double)> pinTrajectory;
  double startTime = 0.0;
  std::vector<int> pinSource;
  int dragDof = -1;  // free DOF of the grabbed vertex, -1 = none
  Eigen::Vector3d dragTarget = Eigen::Vector3d::Zero();
  std::unique_ptr<AvatarContacts> avatar;  // null without a collider
  std::vector<char> seamClosing;            // per free DOF: on a stitch still open at the step's end (scratch)
  std::unique_ptr<ClothContacts> cloth;    // null unless settings.selfCollision
  ContactAccumulator accumulator;
  ContactWarmStart contactWarm;       // last contact forces (settings.contactWarmStart)
  std::unique_ptr<AndersonMixer> anderson;  // settings.andersonWindow > 0
  std::vector<int> lastContactDofs;   // contact set of the previous L-G iteration, for the churn count
  std::vector<char> churnScratch;

  // One step, redone at half the time step while the L-G loop hits its cap and settings.maxHalvings allows;
  // after settings.growAfterSteps converged steps the time step doubles back (towards settings.timeStep).
  PreviewReport step();
  // One attempt at the current level's time step; commits x, v and time unless it diverged or was cancelled.
  PreviewReport attempt();
  // Makes level k (time step settings.timeStep / 2^k) current, building it on first use.
  void useLevel(int k);
  // seamClosing: the free DOFs on a stitch whose sides are still farther apart than kClosingSeamGap contact
  // thicknesses at x. Such a vertex is pulled across the body by its seam, and the step-end fail-safe leaves it to
  // the constraints: putting it back on the surface alone, while its partner is pulled on, stretches the triangles
  // between them. The gap is chosen by measurement on GarmentCode's shirt (docs/EXTREMES.md).
  static constexpr double kClosingSeamGap = 4.0;
  void markClosingSeams();
  // Appends the grabbed vertex's constraint (replacing a contact on the same DOF).
  void addDrag(ContactSet& contacts) const;
  // Contact constraints of one L-G iteration: vertices at the collision-free xFree (|free| x 3), cloth triangles
  // at the last iterate x.
  ContactSet detectContacts(const Eigen::MatrixX3d& xFree, PreviewReport& rep);
  // End of a step: projects x out of the cloth-cloth crossings and thickness violations left by the L-G
  // iterations (ClothContacts::resolve). Vertices in contact with the avatar weigh 1 / kAvatarHold of their mass
  // less in sharing a correction, so a layer lying on the body is not pushed into it.
  void resolveClothContacts(const Eigen::MatrixX3d& start, PreviewReport& rep);
};

PreviewSolver::PreviewSolver(const model::ClothModel& model, const PreviewSettings& settings,
                             std::shared_ptr<const collision::AvatarCollider> collider)
    : m_impl(std::make_unique<Impl>()) {
  Impl& im = *m_impl;
  im.settings = settings;
  im.collider = std::move(collider);
  const int threads = settings.threads > 0 ? settings.threads : tbb::info::default_concurrency();
  im.arena = std::make_unique<tbb::task_arena>(threads);
  im.model = model;
  im.levels.resize(static_cast<size_t>(std::max(settings.maxHalvings, 0)) + 1);
  im.levels[0].system = std::make_unique<PdSystem>(im.model, settings);
  im.system = im.levels[0].system.get();
  const int nv = model.numVertices();
  im.x = asRows(model.positions, nv);
  im.v = model.velocities.size() == 3 * nv ? asRows(model.velocities, nv) : Eigen::MatrixX3d::Zero(nv, 3);
  const auto& pins = im.system->pinnedVertices();
  for (size_t p = 0; p < pins.size(); ++p) im.x.row(pins[p]) = im.system->pinTargets().row(static_cast<int>(p));
  im.pinTrajectory = model.pinTrajectory;
  im.startTime = model.startTime;
  for (int vtx : pins)
    im.pinSource.push_back(static_cast<int>(std::find(model.pinned.begin(), model.pinned.end(), vtx) - model.pinned.begin()));
  const int requested = settings.domains > 0 ? settings.domains : threads;
  im.domains = std::clamp(requested, 1, std::max(im.system->triangleCount(), 1));
  im.arena->execute([&] {
    im.triangleDomain =
        partitionTriangles(model.triangles, nv, model.stitches, model.edgeStitches, im.domains, settings.seed);
    im.useLevel(0);
  });
  // A contact outweighs the fabric and the stitches, however stiff the fabric (contactWeightFor).
  const double stretch = im.system->largestStretch();
  if (im.collider)
    im.avatar = std::make_unique<AvatarContacts>(
        im.collider, AvatarContactOptions{settings.contactThickness, settings.contactMargin,
                                          contactWeightFor(settings.contactWeight, stretch),
                                          settings.friction, settings.ccd, settings.holdContactTargets,
                                          settings.contactTargets, settings.frictionLoad});
  if (settings.selfCollision)
    im.cloth = std::make_unique<ClothContacts>(
        model.triangles, nv, model.stitches, im.system->dofOfVertex(),
        ClothContactOptions{settings.contactThickness, settings.contactMargin,
                            contactWeightFor(settings.selfContactWeight, stretch)},
        model.edgeStitches);
  if (settings.andersonWindow > 0) im.anderson = std::make_unique<AndersonMixer>(settings.andersonWindow);
  im.accumulator.reset(im.system->freeCount());
  toFlat(im.x, im.flatX);
  toFlat(im.v, im.flatV);
}

PreviewSolver::~PreviewSolver() = default;

PreviewReport PreviewSolver::step() {
  PreviewReport report;
  m_impl->arena->execute([&] { report = m_impl->step(); });
  return report;
}

ContactSet PreviewSolver::Impl::detectContacts(const Eigen::MatrixX3d& xFree, PreviewReport& rep) {
  accumulator.reset(system->freeCount());
  rep.ccdContacts = rep.staticFriction = rep.selfContacts = 0;
  if (avatar) {
    const AvatarContactStats st = avatar->addConstraints(xFree, accumulator);
    rep.ccdContacts = st.ccdContacts;
    rep.staticFriction = st.staticFriction;
  }
  if (cloth) rep.selfContacts = cloth->addConstraints(xFree, x, accumulator).contacts;
  return accumulator.merged();
}

void PreviewSolver::Impl::resolveClothContacts(const Eigen::MatrixX3d& start, PreviewReport& rep) {
  constexpr double kAvatarHold = 50.0;
  const auto& dof = system->dofOfVertex();
  const Eigen::VectorXd& mass = system->masses();
  std::vector<double> cache(dof.size(), -1.0);  // inverse masses, computed on first use
  const auto inverseMass = [&](int vtx) {
    double& w = cache[vtx];
    if (w >= 0.0) return w;
    w = dof[vtx] < 0 || !(mass[vtx] > 0.0) ? 0.0 : 1.0 / mass[vtx];
    collision::SurfacePoint sp;
    if (w > 0.0 && collider && collider->closest(x.row(vtx).transpose(), sp, settings.contactThickness))
      w /= kAvatarHold;
    return w;
  };
  const ClothResolveStats st = cloth->resolve(start, x, inverseMass);
  rep.selfResolved = st.violations;
  rep.selfCrossed = st.remaining;
}

void PreviewSolver::Impl::markClosingSeams() {
  const auto& dof = system->dofOfVertex();
  seamClosing.assign(system->freeCount(), 0);
  const double open = kClosingSeamGap * settings.contactThickness, open2 = open * open;
  const auto mark = [&](int vtx) {
    if (dof[vtx] >= 0) seamClosing[dof[vtx]] = 1;
  };
  for (const auto& [a, b] : model.stitches)
    if ((x.row(a) - x.row(b)).squaredNorm() > open2) mark(a), mark(b);
  for (const model::EdgeStitch& e : model.edgeStitches)
    if ((x.row(e.vertex) - (1.0 - e.t) * x.row(e.a) - e.t * x.row(e.b)).squaredNorm() > open2)
      mark(e.vertex), mark(e.a), mark(e.b);
}

void PreviewSolver::Impl::useLevel(int k) {
  Level& lv = levels[k];
  if (!lv.system) {
    PreviewSettings s = settings;
    s.timeStep = std::ldexp(settings.timeStep, -k);
    lv.system = std::make_unique<PdSystem>(model, s);  // moving pins: attempt() sets the targets
  }
  if (!lv.global) {
    if (settings.globalSolver == GlobalSolverKind::Monolithic)
      lv.global = std::make_unique<MonolithicSolver>(lv.system->matrix());
    else
      lv.global = std::make_unique<DomainDecomposedSolver>(splitSystem(*lv.system, triangleDomain, domains),
                                                           lv.system->freeCount(), settings.extraCornerStride);
    lv.local = std::make_unique<LocalStep>(*lv.system, triangleDomain, domains, settings.traversalOrders,
                                           settings.seed);
  }
  level = k;
  convergedInARow = 0;
  system = lv.system.get();
  global = lv.global.get();
  local = lv.local.get();
}

PreviewReport PreviewSolver::Impl::step() {
  const auto start = Clock::now();
  const Eigen::MatrixX3d x0 = x, v0 = v;
  const double time0 = time;
  PreviewReport total;
  for (int splits = 0;; ++splits) {
    PreviewReport rep = attempt();
    addWork(total, rep);  // the last attempt's state, the work of every attempt
    rep.splits = splits;
    total = rep;
    if (rep.status != PreviewStatus::MaxIterations || level + 1 >= static_cast<int>(levels.size())) break;
    x = x0;
    v = v0;
    time = time0;
    useLevel(level + 1);
  }
  if (total.status == PreviewStatus::Converged) {
    if (++convergedInARow >= settings.growAfterSteps && level > 0) useLevel(level - 1);
  } else {
    convergedInARow = 0;
  }
  const bool kept = total.status == PreviewStatus::Converged || total.status == PreviewStatus::MaxIterations;
  if (!sewn && kept && settings.sewnGap > 0.0) {
    if (largestStitchGap(model, x) >= settings.sewnGap) closedSince = -1.0;
    else if (closedSince < 0.0) closedSince = time;
  }
  if (!sewn && closedSince >= 0.0 && time - closedSince >= settings.sewnTime &&
      total.status == PreviewStatus::Converged) {
    sewn = true;
    if (avatar) {
      avatar->setHoldTargets(true);
      avatar->setFrictionLoad(FrictionLoadKind::CollisionFree);
    }
  }
  total.sewn = sewn;
  toFlat(x, flatX);
  toFlat(v, flatV);
  total.wallTime = seconds(start, Clock::now());
  return total;
}

PreviewReport PreviewSolver::Impl::attempt() {
  const auto start = Clock::now();
  PreviewReport rep;
  rep.timeStep = system->timeStep();
  rep.domains = domains;
  if (pinTrajectory) {  // pins where they are at the end of the step
    Eigen::MatrixX3d moved(static_cast<int>(pinSource.size()), 3);
    for (size_t k = 0; k < pinSource.size(); ++k)
      moved.row(static_cast<int>(k)) = pinTrajectory(pinSource[k], startTime + time + system->timeStep()).transpose();
    system->setPinTargets(moved);
  }
  const PdSystem& sys = *system;
  const double h = sys.timeStep();
  const auto& freeVertices = sys.freeVertices();
  const int nf = sys.freeCount();
  const Eigen::MatrixX3d xPrev = x, vPrev = v;
  if (!global->ok()) {  // a factorisation failed: nothing sensible to do
    rep.status = PreviewStatus::Diverged;
    return rep;
  }
  auto restore = [&](PreviewStatus status) {
    x = xPrev;
    v = vPrev;
    rep.status = status;
  };

  // Held targets (preview_settings.h): in every step once sewn, before that in steps up to holdTargetsStep.
  if (avatar && !sewn && !settings.holdContactTargets)
    avatar->setHoldTargets(h <= settings.holdTargetsStep * (1.0 + 1e-9));

  // Inertial prediction z = x + h v + h^2 g (eq. 1); pins at their targets.
  Eigen::MatrixX3d z = x + h * v;
  z.rowwise() += (h * h * sys.gravity()).transpose();
  const auto& pins = sys.pinnedVertices();
  for (size_t p = 0; p < pins.size(); ++p) z.row(pins[p]) = sys.pinTargets().row(static_cast<int>(p));
  const BoundingBox box = boundsOf(x);
  const double extent = std::max(box.size().maxCoeff(), 1e-9);

  // Broad phase of the step: vertices that may reach the avatar, cloth vertex-triangle pairs that may meet.
  if (avatar || cloth) {
    const auto t0 = Clock::now();
    if (avatar) avatar->beginStep(x, z, freeVertices);
    if (cloth) cloth->beginStep(x, z);
    rep.collisionTime += seconds(t0, Clock::now());
  }
  // Avatar: always watched, since internal forces (stitches) can carry any vertex into the body within a step.
  const bool watchContacts = avatar || (cloth && cloth->candidateCount() > 0);

  x = z;
  Eigen::MatrixX3d b;
  const LocalStepKind localKind = sewn ? settings.sewnLocalStep : settings.localStep;
  if (localKind == LocalStepKind::GaussSeidel) {
    const auto t0 = Clock::now();
    local->jacobi(x, targets);
    b = sys.rhs(z, targets);
    rep.localTime += seconds(t0, Clock::now());
  }
  Eigen::MatrixX3d xFree;
  ContactSet contacts;
  if (anderson) anderson->reset();
  rep.status = PreviewStatus::MaxIterations;
  for (int it = 0; it < settings.maxIterations; ++it) {
    if (cancel.exchange(false)) {
      restore(PreviewStatus::Cancelled);
      break;
    }
    auto t0 = Clock::now();
    if (localKind == LocalStepKind::GaussSeidel)
      local->gaussSeidel(x, b, it, targets);
    else
      local->jacobi(x, targets);
    b = sys.rhs(z, targets);
    auto t1 = Clock::now();
    rep.localTime += seconds(t0, t1);
    global->solve(b, xFree);
    auto t2 = Clock::now();
    rep.globalTime += seconds(t1, t2);
    if (watchContacts || dragDof >= 0) {
      if (watchContacts) contacts = detectContacts(xFree, rep);
      else contacts = ContactSet{};
      rep.contacts = contacts.size();
      if (it > 0) rep.contactChurn += contactChurn(lastContactDofs, contacts, churnScratch);
      lastContactDofs = contacts.dofs;
      addDrag(contacts);
      const auto t3 = Clock::now();
      const ContactSolveStats cs = solveContacts(contacts, b, xFree);
      rep.contactSolveTime += seconds(t3, Clock::now());
      rep.contactResidual = cs.relativeResidual;
      rep.sdIterations += cs.sdIterations;
      rep.pcgIterations += cs.pcgIterations;
      rep.collisionTime += seconds(t2, Clock::now());
    }
    rep.iterations = it + 1;
    if (!xFree.allFinite()) {
      restore(PreviewStatus::Diverged);
      break;
    }
    double move = 0.0;
    for (int d = 0; d < nf; ++d) move = std::max(move, (xFree.row(d) - x.row(freeVertices[d])).squaredNorm());
    rep.residual = std::sqrt(move) / extent;
    const bool converged = rep.residual < settings.tolerance && rep.iterations >= settings.minIterations;
    if (anderson && !converged && it + 1 < settings.maxIterations) {
      Eigen::MatrixX3d current(nf, 3);
      for (int d = 0; d < nf; ++d) current.row(d) = x.row(freeVertices[d]);
      xFree = anderson->next(current, xFree);
    }
    for (int d = 0; d < nf; ++d) x.row(freeVertices[d]) = xFree.row(d);
    if (converged) {
      rep.status = PreviewStatus::Converged;
      break;
    }
  }
  if (cloth && (rep.status == PreviewStatus::Converged || rep.status == PreviewStatus::MaxIterations)) {
    const auto t0 = Clock::now();
    resolveClothContacts(xPrev, rep);
    rep.collisionTime += seconds(t0, Clock::now());
  }
  // Last, so that nothing moves a vertex back into the body after it: the body is the harder invariant.
  if (avatar && (rep.status == PreviewStatus::Converged || rep.status == PreviewStatus::MaxIterations)) {
    const auto t0 = Clock::now();
    markClosingSeams();
    rep.avatarResolved = avatar->resolve(x, freeVertices, &seamClosing);
    rep.collisionTime += seconds(t0, Clock::now());
  }
  if (rep.status == PreviewStatus::Converged || rep.status == PreviewStatus::MaxIterations) {
    v = (x - xPrev) * ((1.0 - settings.velocityDamping) / h);
    if (startTime + time < settings.relaxationTime) v.setZero();  // quasi-static assembly
    if (!v.allFinite() || !x.allFinite()) restore(PreviewStatus::Diverged);
    else time += h;
  }
  rep.wallTime = seconds(start, Clock::now());
  return rep;
}

ContactSolveStats PreviewSolver::Impl::solveContacts(const ContactSet& contacts, const Eigen::MatrixX3d& b,
                                                     Eigen::MatrixX3d& xFree) {
  if (settings.contactSolve == ContactSolveKind::Factor) {
    Level& lv = levels[level];
    if (!lv.contactFactor) lv.contactFactor = std::make_unique<ContactFactor>(system->matrix());
    // On failure (not positive definite: cannot happen for K + diagonal) xFree is left as it was: the iterative solve.
    if (lv.contactFactor->solve(contacts, xFree, &b)) return {};
  }
  const ContactSolveKind kind =
      settings.contactSolve == ContactSolveKind::Factor ? ContactSolveKind::DualCgThenPcg : settings.contactSolve;
  return solveWithContacts(system->matrix(), *global, contacts, kind, settings.maxPcgIterations, settings.pcgTolerance,
                           xFree, settings.sdIterations, settings.contactWarmStart ? &contactWarm : nullptr,
                           settings.maxDualIterations);
}

void PreviewSolver::Impl::addDrag(ContactSet& contacts) const {
  if (dragDof < 0) return;
  auto it = std::find(contacts.dofs.begin(), contacts.dofs.end(), dragDof);
  if (it != contacts.dofs.end()) {
    const int k = static_cast<int>(it - contacts.dofs.begin());
    contacts.targets.row(k) = dragTarget.transpose();
    contacts.weights[k] = settings.dragWeight;
    return;
  }
  contacts.dofs.push_back(dragDof);
  contacts.weights.push_back(settings.dragWeight);
  contacts.targets.conservativeResize(contacts.size(), 3);
  contacts.targets.row(contacts.size() - 1) = dragTarget.transpose();
}

void PreviewSolver::setDrag(int vertex, const Eigen::Vector3d& target) {
  Impl& im = *m_impl;
  if (vertex >= im.system->vertexCount()) throw std::invalid_argument("drag: vertex index out of range");
  im.dragDof = vertex < 0 ? -1 : im.system->dofOfVertex()[vertex];
  im.dragTarget = target;
}

void PreviewSolver::requestCancel() { m_impl->cancel = true; }
void PreviewSolver::clearCancel() { m_impl->cancel = false; }
const Eigen::VectorXd& PreviewSolver::positions() const { return m_impl->flatX; }
const Eigen::VectorXd& PreviewSolver::velocities() const { return m_impl->flatV; }
const std::vector<int>& PreviewSolver::triangleDomain() const { return m_impl->triangleDomain; }
int PreviewSolver::domainCount() const { return m_impl->domains; }
double PreviewSolver::time() const { return m_impl->time; }
const PreviewSettings& PreviewSolver::settings() const { return m_impl->settings; }

}  // namespace drape::pd
