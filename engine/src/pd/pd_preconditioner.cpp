#include "drape/pd/pd_preconditioner.h"

#include <algorithm>
#include <cmath>
#include <tbb/info.h>

#include "drape/pd/contact_factor.h"
#include "drape/pd/contact_solve.h"
#include "drape/pd/dd_solver.h"
#include "drape/pd/domain_partition.h"
#include "drape/pd/global_solver.h"
#include "drape/pd/pd_system.h"

namespace drape::pd {
namespace {

// How far apart two positive values are, as a factor (>= 1).
double spread(double a, double b) { return a > b ? a / b : b / a; }

// Refactorisation when h or the stiffness scale moved by more than this factor from the factorised ones.
constexpr double kRefactorSpread = 2.0;

// Within a step a vertex's changing stiffness enters H0 once it is this many times what H0 holds there (its changing
// stiffness, or K's diagonal).
constexpr double kStiffenFactor = 16.0;

// A changing stiffness rounded to a power of 4: the factor is updated only for the vertices whose stiffness moved that
// far, not for every small change of a contact's or friction's stiffness from one step to the next.
double quantised(double k) { return std::exp2(2.0 * std::round(0.5 * std::log2(k))); }

}  // namespace

struct PdPreconditioner::Impl {
  model::ClothModel model;
  double stitchStiffness = 0.0;
  double pinStiffness = 0.0;
  double alpha = 0.0, betaStretch = 0.0, betaBend = 0.0;
  GlobalSolverKind kind = GlobalSolverKind::DomainDecomposed;
  int domains = 1;
  std::vector<int> triangleDomain;
  // The factorised K, its h and stiffness scale. factor (a reference to system's matrix) goes before system.
  double factoredH = 0.0;
  double factoredScale = 0.0;
  std::unique_ptr<PdSystem> system;
  std::unique_ptr<GlobalSolver> global;
  std::unique_ptr<ContactFactor> factor;
  bool factorUsed = false;  // the factor holds stiffness from an earlier step: it answers until that is gone
  int factorisations = 0;
  // This step's changing stiffness on free DOFs (zero targets), and the pinned vertices' diagonal (m / h^2 + ...).
  ContactSet stiff;
  std::vector<double> pinnedDiagonal;
  Eigen::MatrixX3d b, x;

  // Per free DOF: K's diagonal, and the changing stiffness H0 holds there (0: none).
  std::vector<double> diagonal, weight;

  bool build(double h, double scale);
  // stiff from weight.
  void collect();
};

void PdPreconditioner::Impl::collect() {
  stiff = ContactSet{};
  for (size_t d = 0; d < weight.size(); ++d)
    if (weight[d] > 0.0) {
      stiff.dofs.push_back(static_cast<int>(d));
      stiff.weights.push_back(weight[d]);
    }
  stiff.targets = Eigen::MatrixX3d::Zero(stiff.size(), 3);
}

bool PdPreconditioner::Impl::build(double h, double scale) {
  factor.reset();
  global.reset();
  system.reset();
  factorUsed = false;
  model::ClothModel scaled = model;
  const double stretch = scale * (1.0 + betaStretch / h), bend = scale * (1.0 + betaBend / h);
  for (model::TriangleFabric& f : scaled.fabrics) {
    f.stretchWarp *= stretch;
    f.stretchWeft *= stretch;
    f.shear *= stretch;
    f.bendWarp *= bend;
    f.bendWeft *= bend;
  }
  PreviewSettings settings;
  settings.timeStep = 1.0 / std::sqrt(1.0 / (h * h) + alpha / h);  // the mass term (1 / h^2 + alpha / h) M
  settings.shearModel = ShearModelKind::Fabric;
  settings.stitchWeight = stitchStiffness;
  system = std::make_unique<PdSystem>(scaled, settings);
  if (kind == GlobalSolverKind::Monolithic)
    global = std::make_unique<MonolithicSolver>(system->matrix());
  else
    global = std::make_unique<DomainDecomposedSolver>(splitSystem(*system, triangleDomain, domains),
                                                      system->freeCount());
  ++factorisations;
  diagonal.assign(system->freeCount(), 0.0);
  for (int d = 0; d < system->freeCount(); ++d) diagonal[d] = system->matrix().coeff(d, d);
  weight.assign(system->freeCount(), 0.0);
  factoredH = h;
  factoredScale = scale;
  return global->ok();
}

PdPreconditioner::PdPreconditioner(const model::ClothModel& model, double stitchStiffness, double pinStiffness,
                                   double alpha, double betaStretch, double betaBend, int domains,
                                   GlobalSolverKind kind)
    : m_impl(std::make_unique<Impl>()) {
  Impl& im = *m_impl;
  im.model = model;
  im.stitchStiffness = stitchStiffness;
  im.pinStiffness = pinStiffness;
  im.alpha = alpha;
  im.betaStretch = betaStretch;
  im.betaBend = betaBend;
  im.kind = kind;
  const int triangles = static_cast<int>(model.triangles.rows());
  const int requested = domains > 0 ? domains : tbb::info::default_concurrency();
  im.domains = std::clamp(requested, 1, std::max(triangles, 1));
  im.triangleDomain = partitionTriangles(model.triangles, model.numVertices(), model.stitches, model.edgeStitches,
                                         im.domains);
}

PdPreconditioner::~PdPreconditioner() = default;

bool PdPreconditioner::prepare(double h, double scale, const Eigen::VectorXd& vertexStiffness) {
  Impl& im = *m_impl;
  const bool refactor =
      !im.system || spread(h, im.factoredH) > kRefactorSpread || spread(scale, im.factoredScale) > kRefactorSpread;
  if (refactor && !im.build(h, scale)) return false;
  const PdSystem& sys = *im.system;
  const std::vector<int>& dof = sys.dofOfVertex();
  const Eigen::VectorXd& mass = sys.masses();
  for (int v = 0; v < sys.vertexCount(); ++v) {
    const int d = dof[v];
    const double k = v < vertexStiffness.size() ? vertexStiffness[v] : 0.0;
    if (d >= 0) im.weight[d] = k > 0.0 ? quantised(k) : 0.0;
  }
  im.collect();
  const std::vector<int>& pinned = sys.pinnedVertices();
  im.pinnedDiagonal.resize(pinned.size());
  for (size_t p = 0; p < pinned.size(); ++p) {
    const int v = pinned[p];
    const double k = v < vertexStiffness.size() ? vertexStiffness[v] : 0.0;
    im.pinnedDiagonal[p] = mass[v] * (1.0 / (h * h) + im.alpha / h) + im.pinStiffness + k;
  }
  return true;
}

void PdPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& d) {
  Impl& im = *m_impl;
  const PdSystem& sys = *im.system;
  const std::vector<int>& free = sys.freeVertices();
  const int nf = sys.freeCount();
  im.b.resize(nf, 3);
  for (int k = 0; k < nf; ++k) im.b.row(k) = r.segment<3>(3 * free[k]).transpose();
  im.x.resize(nf, 3);
  bool solved = false;
  if (im.stiff.size() > 0 || im.factorUsed) {
    if (!im.factor) im.factor = std::make_unique<ContactFactor>(sys.matrix());
    solved = im.factor->solve(im.stiff, im.x, &im.b);
    im.factorUsed = solved && im.stiff.size() > 0;
  }
  if (!solved) im.global->solve(im.b, im.x);
  d.resize(r.size());
  for (int k = 0; k < nf; ++k) d.segment<3>(3 * free[k]) = im.x.row(k).transpose();
  const std::vector<int>& pinned = sys.pinnedVertices();
  for (size_t p = 0; p < pinned.size(); ++p) d.segment<3>(3 * pinned[p]) = r.segment<3>(3 * pinned[p]) / im.pinnedDiagonal[p];
}

bool PdPreconditioner::stiffen(const Eigen::VectorXd& vertexStiffness) {
  Impl& im = *m_impl;
  const PdSystem& sys = *im.system;
  const std::vector<int>& dof = sys.dofOfVertex();
  bool changed = false;
  for (int v = 0; v < sys.vertexCount() && v < vertexStiffness.size(); ++v) {
    const int d = dof[v];
    const double k = vertexStiffness[v];
    if (d < 0 || !(k > 0.0)) continue;
    double& w = im.weight[d];
    if (k > kStiffenFactor * std::max(w, im.diagonal[d])) {
      w = quantised(k);
      changed = true;
    }
  }
  if (changed) im.collect();
  return true;
}

int PdPreconditioner::factorisations() const {
  const Impl& im = *m_impl;
  return im.factorisations + (im.factor ? im.factor->factorisations() : 0);
}

int PdPreconditioner::domainCount() const { return m_impl->domains; }

const std::vector<int>& PdPreconditioner::triangleDomain() const { return m_impl->triangleDomain; }

}  // namespace drape::pd
