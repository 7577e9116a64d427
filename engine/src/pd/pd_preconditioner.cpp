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

// A changing stiffness rounded to a power of 4: the factor is updated only for the vertices whose stiffness moved that
// far, not for every small change of a contact's or friction's stiffness from one iteration to the next.
// Within a step a vertex's stiffness enters H0 once it is this many times what H0 holds there (its changing stiffness,
// or its mass term where it has none).
constexpr double kStiffenFactor = 16.0;

double quantised(double k) { return std::exp2(2.0 * std::round(0.5 * std::log2(k))); }

}  // namespace

struct PdPreconditioner::Impl {
  newton::ClothModel model;
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

  bool build(double h, double scale);
};

bool PdPreconditioner::Impl::build(double h, double scale) {
  factor.reset();
  global.reset();
  system.reset();
  factorUsed = false;
  newton::ClothModel scaled = model;
  const double stretch = scale * (1.0 + betaStretch / h), bend = scale * (1.0 + betaBend / h);
  for (newton::TriangleFabric& f : scaled.fabrics) {
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
  factoredH = h;
  factoredScale = scale;
  return global->ok();
}

PdPreconditioner::PdPreconditioner(const newton::ClothModel& model, double stitchStiffness, double pinStiffness,
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
  if (!im.system || spread(h, im.factoredH) > kRefactorSpread || spread(scale, im.factoredScale) > kRefactorSpread) {
    if (!im.build(h, scale)) return false;
  }
  const PdSystem& sys = *im.system;
  const std::vector<int>& dof = sys.dofOfVertex();
  const Eigen::VectorXd& mass = sys.masses();
  im.stiff = ContactSet{};
  for (int v = 0; v < sys.vertexCount(); ++v) {
    const double k = v < vertexStiffness.size() ? vertexStiffness[v] : 0.0;
    if (dof[v] >= 0 && k > 0.0) {
      im.stiff.dofs.push_back(dof[v]);
      im.stiff.weights.push_back(quantised(k));
    }
  }
  im.stiff.targets = Eigen::MatrixX3d::Zero(im.stiff.size(), 3);
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
  std::vector<double> weight(sys.freeCount(), 0.0);
  for (int k = 0; k < im.stiff.size(); ++k) weight[im.stiff.dofs[k]] = im.stiff.weights[k];
  bool changed = false;
  for (int v = 0; v < sys.vertexCount() && v < vertexStiffness.size(); ++v) {
    const double k = vertexStiffness[v];
    if (dof[v] < 0 || !(k > 0.0)) continue;
    double& w = weight[dof[v]];
    if (k > kStiffenFactor * std::max(w, sys.masses()[v] / (im.factoredH * im.factoredH))) {
      w = quantised(k);
      changed = true;
    }
  }
  if (!changed) return true;
  im.stiff = ContactSet{};
  for (int d = 0; d < sys.freeCount(); ++d)
    if (weight[d] > 0.0) {
      im.stiff.dofs.push_back(d);
      im.stiff.weights.push_back(weight[d]);
    }
  im.stiff.targets = Eigen::MatrixX3d::Zero(im.stiff.size(), 3);
  return true;
}

int PdPreconditioner::factorisations() const {
  const Impl& im = *m_impl;
  return im.factorisations + (im.factor ? im.factor->factorisations() : 0);
}

int PdPreconditioner::domainCount() const { return m_impl->domains; }

const std::vector<int>& PdPreconditioner::triangleDomain() const { return m_impl->triangleDomain; }

}  // namespace drape::pd
