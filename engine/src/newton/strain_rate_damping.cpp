#include "drape/newton/strain_rate_damping.h"

#include <tbb/parallel_for.h>

namespace drape::newton {
namespace {

template <int N>
Eigen::Matrix<double, 3 * N, 1> gatherDelta(const std::array<int, N>& s, const Eigen::VectorXd& x,
                                            const Eigen::VectorXd& x0) {
  Eigen::Matrix<double, 3 * N, 1> d;
  for (int k = 0; k < N; ++k) d.template segment<3>(3 * k) = x.segment<3>(3 * s[k]) - x0.segment<3>(3 * s[k]);
  return d;
}

// Runs f(i) for i in [0, n), in parallel when asked (independent per-stencil work, no shared writes).
template <typename F>
void forRange(int n, bool parallel, const F& f) {
  if (!parallel) {
    for (int i = 0; i < n; ++i) f(i);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 256), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i < r.end(); ++i) f(i);
  });
}

}  // namespace

MembraneDissipation::MembraneDissipation(std::vector<MembraneElement> elements, double beta)
    : m_elements(std::move(elements)), m_beta(beta) {
  std::vector<std::array<int, 3>> stencils;
  stencils.reserve(m_elements.size());
  for (const auto& e : m_elements) stencils.push_back(e.v);
  m_stencils = StencilSet<3>(std::move(stencils));
  m_jacobians.resize(m_elements.size());
  m_weights.assign(m_elements.size(), Eigen::Vector3d::Zero());
}

void MembraneDissipation::beginStep(const StepContext& ctx) {
  beginLagged(ctx);
  const double factor = m_beta * ctx.stiffnessScale / ctx.h;
  forRange(static_cast<int>(m_elements.size()), m_options.parallel, [&](int s) {
    const MembraneElement& e = m_elements[s];
    m_jacobians[s] = greenStrainJacobian(e, *ctx.previousPositions);
    m_weights[s] = (factor * e.area) * Eigen::Vector3d(e.kWarp, e.kWeft, 2.0 * e.kShear);
  });
}

double MembraneDissipation::value(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (int s = 0; s < m_stencils.size(); ++s) {
    Eigen::Vector3d rate = m_jacobians[s] * gatherDelta<3>(m_stencils[s], x, *m_previous);
    sum += 0.5 * rate.dot(m_weights[s].cwiseProduct(rate));
  }
  return sum;
}

Eigen::Matrix<double, 9, 1> MembraneDissipation::stencilGradient(int s, const Eigen::VectorXd& x) const {
  const Eigen::Vector3d rate = m_jacobians[s] * gatherDelta<3>(m_stencils[s], x, *m_previous);
  return m_jacobians[s].transpose() * m_weights[s].cwiseProduct(rate);
}

void MembraneDissipation::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  if (folded()) return;  // the membrane adds this energy's share in its own pass
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    for (int i = 0; i < count; ++i) m_stencils.addGradient(ids[i], stencilGradient(ids[i], x), g);
  });
}

Eigen::Matrix<double, 9, 9> MembraneDissipation::stencilDerivatives(int s, const Eigen::VectorXd& x,
                                                                    Eigen::Matrix<double, 9, 1>* ge) const {
  Eigen::Matrix<double, 9, 9> he = m_jacobians[s].transpose() * m_weights[s].asDiagonal() * m_jacobians[s];
  if (ge) *ge = he * gatherDelta<3>(m_stencils[s], x, *m_previous);  // quadratic in d = x - x_n
  return he;
}

void MembraneDissipation::addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const { assemble(x, nullptr, h); }

void MembraneDissipation::addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const {
  assemble(x, &g, h);
}

void MembraneDissipation::assemble(const Eigen::VectorXd& x, Eigen::VectorXd* g, BlockMatrix& h) const {
  if (folded()) return;  // the membrane adds this energy's share in its own pass
  const bool cached = m_options.cachedBlockMap;
  if (cached) m_stencils.prepare(h);
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    Eigen::Matrix<double, 9, 1> ge;
    for (int i = 0; i < count; ++i) {
      m_stencils.addHessian(ids[i], stencilDerivatives(ids[i], x, g ? &ge : nullptr), h, cached);
      if (g) m_stencils.addGradient(ids[i], ge, *g);
    }
  });
}

BendingDissipation::BendingDissipation(std::vector<Hinge> hinges, double beta)
    : m_hinges(std::move(hinges)), m_beta(beta) {
  std::vector<std::array<int, 4>> stencils;
  stencils.reserve(m_hinges.size());
  for (const auto& h : m_hinges) stencils.push_back(h.v);
  m_stencils = StencilSet<4>(std::move(stencils));
  m_gradients.assign(m_hinges.size(), Eigen::Matrix<double, 12, 1>::Zero());
  m_coefficients.assign(m_hinges.size(), 0.0);
}

void BendingDissipation::beginStep(const StepContext& ctx) {
  beginLagged(ctx);
  const double factor = m_beta * ctx.stiffnessScale / ctx.h;
  const bool closedForm = m_options.closedFormBending;
  forRange(static_cast<int>(m_hinges.size()), m_options.parallel, [&](int s) {
    double phi = 0.0;
    m_gradients[s] = hingeBendGradient(m_hinges[s], *ctx.previousPositions, closedForm, phi);
    m_coefficients[s] = factor * m_hinges[s].stiffness;
  });
}

double BendingDissipation::value(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (int s = 0; s < m_stencils.size(); ++s) {
    double rate = m_gradients[s].dot(gatherDelta<4>(m_stencils[s], x, *m_previous));
    sum += 0.5 * m_coefficients[s] * rate * rate;
  }
  return sum;
}

Eigen::Matrix<double, 12, 1> BendingDissipation::stencilGradient(int s, const Eigen::VectorXd& x) const {
  return (m_coefficients[s] * m_gradients[s].dot(gatherDelta<4>(m_stencils[s], x, *m_previous))) * m_gradients[s];
}

void BendingDissipation::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  if (folded()) return;  // the hinge bending adds this energy's share in its own pass
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    for (int i = 0; i < count; ++i) m_stencils.addGradient(ids[i], stencilGradient(ids[i], x), g);
  });
}

Eigen::Matrix<double, 12, 12> BendingDissipation::stencilDerivatives(int s, const Eigen::VectorXd& x,
                                                                     Eigen::Matrix<double, 12, 1>* ge) const {
  if (ge) *ge = stencilGradient(s, x);
  return m_coefficients[s] * (m_gradients[s] * m_gradients[s].transpose());
}

void BendingDissipation::addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const { assemble(x, nullptr, h); }

void BendingDissipation::addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const {
  assemble(x, &g, h);
}

void BendingDissipation::assemble(const Eigen::VectorXd& x, Eigen::VectorXd* g, BlockMatrix& h) const {
  if (folded()) return;  // the hinge bending adds this energy's share in its own pass
  const bool cached = m_options.cachedBlockMap;
  if (cached) m_stencils.prepare(h);
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    Eigen::Matrix<double, 12, 1> ge;
    for (int i = 0; i < count; ++i) {
      m_stencils.addHessian(ids[i], stencilDerivatives(ids[i], x, g ? &ge : nullptr), h, cached);
      if (g) m_stencils.addGradient(ids[i], ge, *g);
    }
  });
}

}  // namespace drape::newton
