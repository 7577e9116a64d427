#include "drape/newton/stvk_membrane.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "drape/newton/strain_rate_damping.h"

namespace drape::newton {

Eigen::Matrix<double, 3, 2> deformationGradient(const MembraneElement& e, const Eigen::VectorXd& x) {
  Eigen::Matrix<double, 3, 2> f = Eigen::Matrix<double, 3, 2>::Zero();
  for (int k = 0; k < 3; ++k) f += x.segment<3>(3 * e.v[k]) * e.c[k].transpose();
  return f;
}

namespace {

// Voigt Green strain (E00, E11, E01).
Eigen::Vector3d greenStrain(const Eigen::Matrix<double, 3, 2>& f) {
  return {0.5 * (f.col(0).squaredNorm() - 1.0), 0.5 * (f.col(1).squaredNorm() - 1.0), 0.5 * f.col(0).dot(f.col(1))};
}

Eigen::Vector3d voigtWeights(const MembraneElement& e) { return {e.kWarp, e.kWeft, 2.0 * e.kShear}; }

// J^T sigma without forming J (greenStrainJacobian at f): vertex k gets c_k0 s0 f0 + c_k1 s1 f1 + s2/2 (c_k0 f1 +
// c_k1 f0).
Eigen::Matrix<double, 9, 1> strainGradient(const MembraneElement& e, const Eigen::Matrix<double, 3, 2>& f,
                                           const Eigen::Vector3d& sigma) {
  const Eigen::Vector3d a = sigma(0) * f.col(0) + 0.5 * sigma(2) * f.col(1);
  const Eigen::Vector3d b = sigma(1) * f.col(1) + 0.5 * sigma(2) * f.col(0);
  Eigen::Matrix<double, 9, 1> ge;
  for (int k = 0; k < 3; ++k) ge.segment<3>(3 * k) = e.c[k](0) * a + e.c[k](1) * b;
  return ge;
}

// The positive part of a symmetric 2x2 matrix (its eigenvalues clamped at 0), in closed form: with eigenvalues
// high > 0 > low it is high v v^T = high / (high - low) (s - low I).
Eigen::Matrix2d positivePart(const Eigen::Matrix2d& s) {
  const double mean = 0.5 * (s(0, 0) + s(1, 1)), half = 0.5 * (s(0, 0) - s(1, 1));
  const double radius = std::sqrt(half * half + s(0, 1) * s(0, 1));
  const double high = mean + radius, low = mean - radius;
  if (low >= 0.0) return s;
  if (high <= 0.0) return Eigen::Matrix2d::Zero();
  return (high / (high - low)) * (s - low * Eigen::Matrix2d::Identity());
}

// Adds to blocks (pairs (a, b), a <= b, in StencilSet order) the blocks of J^T diag(w) J, J = greenStrainJacobian at
// f, and, when stress is given, the geometric term (c_a . stress c_b) I: elementDerivatives' Hessian, written block
// by block from f's outer products instead of as a 9 x 9 product. With J_k's rows c_k0 f0, c_k1 f1 and
// (c_k0 f1 + c_k1 f0) / 2, block (a, b) is
//   (w0 c_a0 c_b0 + w2/4 c_a1 c_b1) f0 f0^T + (w1 c_a1 c_b1 + w2/4 c_a0 c_b0) f1 f1^T
//   + w2/4 (c_a1 c_b0 f0 f1^T + c_a0 c_b1 f1 f0^T).
void addStrainHessianBlocks(const MembraneElement& e, const Eigen::Matrix<double, 3, 2>& f, const Eigen::Vector3d& w,
                            const Eigen::Matrix2d* stress, std::array<Eigen::Matrix3d, 6>& blocks) {
  const Eigen::Matrix3d p00 = f.col(0) * f.col(0).transpose(), p11 = f.col(1) * f.col(1).transpose();
  const Eigen::Matrix3d p01 = f.col(0) * f.col(1).transpose();
  const double q = 0.25 * w(2);
  int p = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b, ++p) {
      const Eigen::Vector2d &ca = e.c[a], &cb = e.c[b];
      blocks[p] += (w(0) * ca(0) * cb(0) + q * ca(1) * cb(1)) * p00 + (w(1) * ca(1) * cb(1) + q * ca(0) * cb(0)) * p11 +
                   (q * ca(1) * cb(0)) * p01 + (q * ca(0) * cb(1)) * p01.transpose();
      if (stress) blocks[p].diagonal().array() += ca.dot(*stress * cb);
    }
}

}  // namespace

std::vector<MembraneElement> buildMembraneElements(const model::ClothModel& model) {
  std::vector<MembraneElement> out(model.triangles.rows());
  for (int t = 0; t < model.triangles.rows(); ++t) {
    MembraneElement& e = out[t];
    for (int k = 0; k < 3; ++k) e.v[k] = model.triangles(t, k);
    Eigen::Vector2d u0 = model.restCoords.row(e.v[0]).transpose();
    Eigen::Matrix2d dm;
    dm.col(0) = model.restCoords.row(e.v[1]).transpose() - u0;
    dm.col(1) = model.restCoords.row(e.v[2]).transpose() - u0;
    double det = dm.determinant();
    if (!(std::abs(det) > 1e-14))
      throw std::invalid_argument("cloth model: triangle " + std::to_string(t) + " has zero rest area");
    Eigen::Matrix2d inv = dm.inverse();
    e.c[1] = inv.row(0).transpose();
    e.c[2] = inv.row(1).transpose();
    e.c[0] = -(e.c[1] + e.c[2]);
    e.area = 0.5 * std::abs(det);
    const model::TriangleFabric& fab = model.fabric(t);
    e.kWarp = fab.stretchWarp;
    e.kWeft = fab.stretchWeft;
    e.kShear = fab.shear;
  }
  return out;
}

Eigen::Matrix<double, 3, 9> greenStrainJacobian(const MembraneElement& e, const Eigen::Matrix<double, 3, 2>& f) {
  Eigen::Matrix<double, 3, 9> j;
  for (int k = 0; k < 3; ++k) {
    j.block<1, 3>(0, 3 * k) = e.c[k](0) * f.col(0).transpose();
    j.block<1, 3>(1, 3 * k) = e.c[k](1) * f.col(1).transpose();
    j.block<1, 3>(2, 3 * k) = 0.5 * (e.c[k](0) * f.col(1) + e.c[k](1) * f.col(0)).transpose();
  }
  return j;
}

Eigen::Matrix<double, 3, 9> greenStrainJacobian(const MembraneElement& e, const Eigen::VectorXd& x) {
  return greenStrainJacobian(e, deformationGradient(e, x));
}

StvkMembrane::StvkMembrane(const model::ClothModel& model) : m_elements(buildMembraneElements(model)) {
  std::vector<std::array<int, 3>> stencils;
  stencils.reserve(m_elements.size());
  for (const auto& e : m_elements) stencils.push_back(e.v);
  m_stencils = StencilSet<3>(std::move(stencils));
}

void StvkMembrane::beginStep(const StepContext& ctx) {
  m_scale = ctx.stiffnessScale;
  m_options = ctx.assembly;
}

double StvkMembrane::value(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (const auto& e : m_elements) {
    Eigen::Vector3d s = greenStrain(deformationGradient(e, x));
    sum += e.area * 0.5 * s.cwiseProduct(voigtWeights(e)).dot(s);
  }
  return m_scale * sum;
}

void StvkMembrane::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const { gradientPass(x, g, true); }

void StvkMembrane::gradientPass(const Eigen::VectorXd& x, Eigen::VectorXd& g, bool recordPass) const {
  const MembraneDissipation* fold = m_options.foldDissipation ? m_dissipation : nullptr;
  const bool record = recordPass && m_recorded.enabled;
  const bool recordF = recordPass && m_recordF;
  if (record) m_recorded.begin(x.size());
  if (recordF) {
    m_recordedF.resize(m_elements.size());
    m_recordedFAt.resize(0);  // invalid until the pass is complete
  }
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    if (m_options.batchedGradients) {
      batchGradients(x, ids, count, recordF, record ? &m_recorded.gradient : nullptr, fold, g);
      return;
    }
    Eigen::Matrix<double, 9, 1> ge;
    for (int i = 0; i < count; ++i) {
      const MembraneElement& e = m_elements[ids[i]];
      const Eigen::Matrix<double, 3, 2> f = deformationGradient(e, x);
      if (recordF) m_recordedF[ids[i]] = f;
      ge = strainGradient(e, f, (m_scale * e.area) * greenStrain(f).cwiseProduct(voigtWeights(e)));
      if (record) m_stencils.addGradient(ids[i], ge, m_recorded.gradient);
      if (fold) ge += fold->stencilGradient(ids[i], e, f);
      m_stencils.addGradient(ids[i], ge, g);
    }
  });
  if (record) m_recorded.finish(x, m_scale);
  if (recordF) m_recordedFAt = x;
}

// The per-triangle loop of gradientPass, kLanes triangles at a time: every quantity an array over the lanes, so
// that the compiler vectorises the arithmetic across triangles (the gathers and scatters stay scalar).
void StvkMembrane::batchGradients(const Eigen::VectorXd& x, const int* ids, int count, bool recordF,
                                  Eigen::VectorXd* recordedGradient, const MembraneDissipation* fold,
                                  Eigen::VectorXd& g) const {
  const double foldFactor = fold ? fold->factor() : 0.0;
  constexpr int kLanes = 8;
  for (int i0 = 0; i0 < count; i0 += kLanes) {
    const int lanes = std::min(kLanes, count - i0);
    // The next batch's elements and folded start F, requested ahead (see HingeBending::batchGradients).
    for (int l = 0; l < kLanes && i0 + kLanes + l < count; ++l) {
      const int s = ids[i0 + kLanes + l];
      prefetchRange(&m_elements[s], sizeof(MembraneElement));
      if (fold) prefetchRange(fold->startF(s).data(), sizeof(Eigen::Matrix<double, 3, 2>));
    }
    alignas(64) double p[9][kLanes], c[6][kLanes], k[3][kLanes], fn[6][kLanes], f[6][kLanes], ge[9][kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const bool live = l < lanes;
      const MembraneElement& e = m_elements[ids[i0 + (live ? l : 0)]];
      for (int v = 0; v < 3; ++v) {
        const double* xv = x.data() + 3 * e.v[v];
        for (int d = 0; d < 3; ++d) p[3 * v + d][l] = xv[d];
        c[2 * v][l] = live ? e.c[v](0) : 0.0;
        c[2 * v + 1][l] = live ? e.c[v](1) : 0.0;
      }
      k[0][l] = e.area * e.kWarp;
      k[1][l] = e.area * e.kWeft;
      k[2][l] = e.area * 2.0 * e.kShear;
      if (fold) {
        const Eigen::Matrix<double, 3, 2>& start = fold->startF(ids[i0 + (live ? l : 0)]);
        for (int j = 0; j < 6; ++j) fn[j][l] = start.data()[j];
      }
    }
    const double scale = m_scale;
    for (int l = 0; l < kLanes; ++l) {
      for (int d = 0; d < 3; ++d) {
        f[d][l] = p[d][l] * c[0][l] + p[3 + d][l] * c[2][l] + p[6 + d][l] * c[4][l];
        f[3 + d][l] = p[d][l] * c[1][l] + p[3 + d][l] * c[3][l] + p[6 + d][l] * c[5][l];
      }
      const double f00 = f[0][l] * f[0][l] + f[1][l] * f[1][l] + f[2][l] * f[2][l];
      const double f11 = f[3][l] * f[3][l] + f[4][l] * f[4][l] + f[5][l] * f[5][l];
      const double f01 = f[0][l] * f[3][l] + f[1][l] * f[4][l] + f[2][l] * f[5][l];
      const double s0 = scale * k[0][l] * 0.5 * (f00 - 1.0), s1 = scale * k[1][l] * 0.5 * (f11 - 1.0);
      const double s2 = scale * k[2][l] * 0.5 * f01;
      double a[3], b[3];
      for (int d = 0; d < 3; ++d) {
        a[d] = s0 * f[d][l] + 0.5 * s2 * f[3 + d][l];
        b[d] = s1 * f[3 + d][l] + 0.5 * s2 * f[d][l];
      }
      for (int v = 0; v < 3; ++v)
        for (int d = 0; d < 3; ++d) ge[3 * v + d][l] = c[2 * v][l] * a[d] + c[2 * v + 1][l] * b[d];
    }
    for (int l = 0; l < lanes; ++l) {
      const int s = ids[i0 + l];
      if (recordF)
        for (int j = 0; j < 6; ++j) m_recordedF[s].data()[j] = f[j][l];
      if (recordedGradient) {
        const MembraneElement& e = m_elements[s];
        for (int v = 0; v < 3; ++v)
          for (int d = 0; d < 3; ++d) (*recordedGradient)[3 * e.v[v] + d] += ge[3 * v + d][l];
      }
    }
    if (fold) {
      for (int l = 0; l < kLanes; ++l) {
        double df[6];
        for (int j = 0; j < 6; ++j) df[j] = f[j][l] - fn[j][l];
        const double r0 = fn[0][l] * df[0] + fn[1][l] * df[1] + fn[2][l] * df[2];
        const double r1 = fn[3][l] * df[3] + fn[4][l] * df[4] + fn[5][l] * df[5];
        const double r2 = 0.5 * (fn[0][l] * df[3] + fn[1][l] * df[4] + fn[2][l] * df[5] + fn[3][l] * df[0] +
                                 fn[4][l] * df[1] + fn[5][l] * df[2]);
        const double s0 = foldFactor * k[0][l] * r0, s1 = foldFactor * k[1][l] * r1, s2 = foldFactor * k[2][l] * r2;
        double a[3], b[3];
        for (int d = 0; d < 3; ++d) {
          a[d] = s0 * fn[d][l] + 0.5 * s2 * fn[3 + d][l];
          b[d] = s1 * fn[3 + d][l] + 0.5 * s2 * fn[d][l];
        }
        for (int v = 0; v < 3; ++v)
          for (int d = 0; d < 3; ++d) ge[3 * v + d][l] += c[2 * v][l] * a[d] + c[2 * v + 1][l] * b[d];
      }
    }
    for (int l = 0; l < lanes; ++l) {
      const MembraneElement& e = m_elements[ids[i0 + l]];
      for (int v = 0; v < 3; ++v) {
        double* gv = g.data() + 3 * e.v[v];
        for (int d = 0; d < 3; ++d) gv[d] += ge[3 * v + d][l];
      }
    }
  }
}

bool StvkMembrane::takeRecordedDeformationGradients(const Eigen::VectorXd& x,
                                                    std::vector<Eigen::Matrix<double, 3, 2>>& f) const {
  if (!samePositions(m_recordedFAt, x) || m_recordedF.size() != m_elements.size()) return false;
  f.swap(m_recordedF);
  m_recordedFAt.resize(0);
  return true;
}

Eigen::Matrix<double, 9, 9> StvkMembrane::elementHessian(const MembraneElement& e, const Eigen::VectorXd& x) const {
  return elementDerivatives(e, x, nullptr);
}

Eigen::Matrix<double, 9, 9> StvkMembrane::elementDerivatives(const MembraneElement& e, const Eigen::VectorXd& x,
                                                             Eigen::Matrix<double, 9, 1>* ge) const {
  return elementDerivatives(e, deformationGradient(e, x), ge);
}

Eigen::Matrix<double, 9, 9> StvkMembrane::elementDerivatives(const MembraneElement& e,
                                                             const Eigen::Matrix<double, 3, 2>& f,
                                                             Eigen::Matrix<double, 9, 1>* ge) const {
  Eigen::Vector3d sigma = greenStrain(f).cwiseProduct(voigtWeights(e));  // dpsi/ds in Voigt form
  Eigen::Matrix<double, 3, 9> j = greenStrainJacobian(e, f);
  if (ge) *ge = (m_scale * e.area) * j.transpose() * sigma;
  Eigen::Matrix<double, 9, 9> h = (j.transpose() * voigtWeights(e).asDiagonal()).lazyProduct(j);  // no GEMM
  // Second Piola-Kirchhoff stress as a symmetric 2x2 tensor.
  Eigen::Matrix2d stress;
  stress << sigma(0), 0.5 * sigma(2), 0.5 * sigma(2), sigma(1);
  if (!m_exactHessian) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(stress);
    Eigen::Vector2d lambda = eig.eigenvalues().cwiseMax(0.0);
    stress = eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
  }
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) h.block<3, 3>(3 * a, 3 * b).diagonal().array() += e.c[a].dot(stress * e.c[b]);
  return (m_scale * e.area) * h;
}

void StvkMembrane::addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const { assemble(x, nullptr, h); }

void StvkMembrane::addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const {
  assemble(x, &g, h);
}

// elementDerivatives (and the folded dissipation's stencilGradient and stencilHessian) per triangle, the Hessian's
// upper blocks written straight from F's outer products (addStrainHessianBlocks), the stress clamped in closed form.
void StvkMembrane::assemble(const Eigen::VectorXd& x, Eigen::VectorXd* g, BlockMatrix& h) const {
  const bool cached = m_options.cachedBlockMap;
  if (cached) m_stencils.prepare(h);
  const MembraneDissipation* fold = m_options.foldDissipation ? m_dissipation : nullptr;
  m_stencils.forEach(m_options.parallel, [&](const int* ids, int count) {
    std::array<Eigen::Matrix3d, 6> blocks;
    for (int i = 0; i < count; ++i) {
      const int s = ids[i];
      if (i + kPrefetchAhead < count) {
        const int next = ids[i + kPrefetchAhead];
        m_stencils.prefetch(next);
        prefetchRange(&m_elements[next], sizeof(MembraneElement));
        if (fold) prefetchRange(fold->startF(next).data(), sizeof(Eigen::Matrix<double, 3, 2>));
      }
      const MembraneElement& e = m_elements[s];
      const Eigen::Matrix<double, 3, 2> f = deformationGradient(e, x);
      const Eigen::Vector3d w = (m_scale * e.area) * voigtWeights(e);
      const Eigen::Vector3d sigma = greenStrain(f).cwiseProduct(w);  // scaled second Piola-Kirchhoff stress, Voigt
      if (g) {
        Eigen::Matrix<double, 9, 1> ge = strainGradient(e, f, sigma);
        if (fold) ge += fold->stencilGradient(s, e, f);
        m_stencils.addGradient(s, ge, *g);
      }
      Eigen::Matrix2d stress;
      stress << sigma(0), 0.5 * sigma(2), 0.5 * sigma(2), sigma(1);
      if (!m_exactHessian) stress = positivePart(stress);
      for (auto& block : blocks) block.setZero();
      addStrainHessianBlocks(e, f, w, &stress, blocks);
      // The stretch dissipation's J_n^T W J_n (MembraneDissipation::stencilHessian), W = c A (kWarp, kWeft, 2 kShear).
      if (fold)
        addStrainHessianBlocks(e, fold->startF(s), (fold->factor() * e.area) * voigtWeights(e), nullptr, blocks);
      m_stencils.addPairBlocks(s, blocks, h, cached);
    }
  });
}

void StvkMembrane::addCouplings(std::vector<std::pair<int, int>>& pairs) const { m_stencils.addCouplings(pairs); }

}  // namespace drape::newton
