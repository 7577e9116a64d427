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
  m_startF.resize(m_elements.size());
}

void MembraneDissipation::beginStep(const StepContext& ctx) {
  beginLagged(ctx);
  m_factor = m_beta * ctx.stiffnessScale / ctx.h;
  const Eigen::VectorXd& xn = *ctx.previousPositions;
  if (m_source && m_source->takeRecordedDeformationGradients(xn, m_startF)) return;
  forRange(static_cast<int>(m_elements.size()), m_options.parallel,
           [&](int s) { m_startF[s] = deformationGradient(m_elements[s], xn); });
}

Eigen::Vector3d MembraneDissipation::strainChange(int s, const Eigen::Matrix<double, 3, 2>& f) const {
  const Eigen::Matrix<double, 3, 2>& fn = m_startF[s];
  const Eigen::Matrix<double, 3, 2> df = f - fn;
  return {fn.col(0).dot(df.col(0)), fn.col(1).dot(df.col(1)),
          0.5 * (fn.col(0).dot(df.col(1)) + fn.col(1).dot(df.col(0)))};
}

double MembraneDissipation::value(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (int s = 0; s < m_stencils.size(); ++s) {
    const Eigen::Vector3d rate = strainChange(s, deformationGradient(m_elements[s], x));
    sum += 0.5 * rate.dot(weights(m_elements[s]).cwiseProduct(rate));
  }
  return sum;
}

Eigen::Matrix<double, 9, 1> MembraneDissipation::stencilGradient(int s, const Eigen::VectorXd& x) const {
  return stencilGradient(s, m_elements[s], deformationGradient(m_elements[s], x));
}

Eigen::Matrix<double, 9, 1> MembraneDissipation::stencilGradient(int s, const MembraneElement& e,
                                                                 const Eigen::Matrix<double, 3, 2>& f) const {
  // J^T sigma without forming J: vertex k gets c_k0 (s0 f0 + s2/2 f1) + c_k1 (s1 f1 + s2/2 f0), f = F_n.
  const Eigen::Vector3d sigma = weights(e).cwiseProduct(strainChange(s, f));
  const Eigen::Matrix<double, 3, 2>& fn = m_startF[s];
  const Eigen::Vector3d a = sigma(0) * fn.col(0) + 0.5 * sigma(2) * fn.col(1);
  const Eigen::Vector3d b = sigma(1) * fn.col(1) + 0.5 * sigma(2) * fn.col(0);
  Eigen::Matrix<double, 9, 1> ge;
  for (int k = 0; k < 3; ++k) ge.segment<3>(3 * k) = e.c[k](0) * a + e.c[k](1) * b;
  return ge;
}

void MembraneDissipation::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  if (folded()) return;  // the membrane adds this energy's share in its own pass
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    for (int i = 0; i < count; ++i) m_stencils.addGradient(ids[i], stencilGradient(ids[i], x), g);
  });
}

Eigen::Matrix<double, 9, 9> MembraneDissipation::stencilHessian(int s, const MembraneElement& e) const {
  const Eigen::Matrix<double, 3, 9> j = greenStrainJacobian(e, m_startF[s]);
  return (j.transpose() * weights(e).asDiagonal()).lazyProduct(j);  // coefficient-based: no GEMM for 9 x 3 x 9
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
    for (int i = 0; i < count; ++i) {
      m_stencils.addHessian(ids[i], stencilHessian(ids[i], m_elements[ids[i]]), h, cached);
      if (g) m_stencils.addGradient(ids[i], stencilGradient(ids[i], x), *g);
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
  m_offsets.assign(m_hinges.size(), 0.0);
}

void BendingDissipation::beginStep(const StepContext& ctx) {
  beginLagged(ctx);
  m_factor = m_beta * ctx.stiffnessScale / ctx.h;
  const bool closedForm = m_options.closedFormBending;
  const Eigen::VectorXd& xn = *ctx.previousPositions;
  if (m_source && m_source->takeRecordedGradients(xn, closedForm, m_gradients, m_offsets)) return;
  forRange(static_cast<int>(m_hinges.size()), m_options.parallel, [&](int s) {
    double phi = 0.0;
    m_gradients[s] = hingeBendGradient(m_hinges[s], xn, closedForm, phi);
    m_offsets[s] = zeroSumOffset(m_hinges[s], xn, m_gradients[s]);
  });
}

double BendingDissipation::angleChange(int s, const HingeCoords& q) const {
  const Eigen::Vector3d x0 = q.segment<3>(0);
  const Eigen::Matrix<double, 12, 1>& g = m_gradients[s];
  double sum = 0.0;
  for (int k = 1; k < 4; ++k) sum += g.segment<3>(3 * k).dot(q.segment<3>(3 * k) - x0);
  return sum - m_offsets[s];
}

double BendingDissipation::value(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (int s = 0; s < m_stencils.size(); ++s) {
    const double rate = angleChange(s, gatherHinge(m_hinges[s], x));
    sum += 0.5 * (m_factor * m_hinges[s].stiffness) * rate * rate;
  }
  return sum;
}

Eigen::Matrix<double, 12, 1> BendingDissipation::stencilGradient(int s, const Eigen::VectorXd& x) const {
  return stencilGradient(s, gatherHinge(m_hinges[s], x), m_hinges[s].stiffness);
}

Eigen::Matrix<double, 12, 1> BendingDissipation::stencilGradient(int s, const HingeCoords& q, double stiffness) const {
  return ((m_factor * stiffness) * angleChange(s, q)) * m_gradients[s];
}

void BendingDissipation::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  if (folded()) return;  // the hinge bending adds this energy's share in its own pass
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    for (int i = 0; i < count; ++i) m_stencils.addGradient(ids[i], stencilGradient(ids[i], x), g);
  });
}

Eigen::Matrix<double, 12, 12> BendingDissipation::stencilDerivatives(int s, const HingeCoords& q, double stiffness,
                                                                     Eigen::Matrix<double, 12, 1>* ge) const {
  if (ge) *ge = stencilGradient(s, q, stiffness);
  return (m_factor * stiffness) * (m_gradients[s] * m_gradients[s].transpose());
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
      const Hinge& hinge = m_hinges[ids[i]];
      m_stencils.addHessian(
          ids[i], stencilDerivatives(ids[i], gatherHinge(hinge, x), hinge.stiffness, g ? &ge : nullptr), h, cached);
      if (g) m_stencils.addGradient(ids[i], ge, *g);
    }
  });
}

}  // namespace drape::newton
