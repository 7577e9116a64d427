#include "drape/pd/dd_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <tbb/parallel_for.h>

#include "drape/pd/sparse_cholesky.h"

namespace drape::pd {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

struct Domain {
  std::vector<int> rGlobal;       // local R -> global DOF
  std::vector<std::uint8_t> rTakesB;  // internal, or duplicate owned by this domain: b goes here
  std::vector<std::uint8_t> rWrites;  // this domain writes x of the DOF
  std::vector<int> cCorner;       // local C -> corner index
  std::vector<int> dupLocal;      // duplicates: local R index
  std::vector<int> dupDual;       //             index into lambda
  std::vector<double> dupSign;    //             +1 owner (lower domain), -1 other
  SpMat kRC, kCC;
  SparseCholesky llt;             // K_RR^j
  // Scratch of solve(), sized once: b_R^j and then x_R^j (N_R^j x 3 row-major), the solver's work array.
  mutable std::vector<double> rhs, work;
};

}  // namespace

struct DomainDecomposedSolver::Impl {
  std::vector<Domain> domains;
  std::vector<DofClass> classes;
  std::vector<int> cornerDof;     // corner index -> DOF
  int nDual = 0;
  SparseCholesky gRR;
  Eigen::MatrixXd gRC;            // nDual x nC
  Eigen::MatrixXd w;              // G_RR^-1 G_RC
  Eigen::LLT<Eigen::MatrixXd> gCCStar;
  // Scratch of solve(): dual right-hand side then lambda (nDual x 3 row-major), its work array; x_C (nC x 3).
  mutable std::vector<double> dual, dualWork;
  mutable Eigen::MatrixX3d bCStar, xC;
};

DomainDecomposedSolver::DomainDecomposedSolver(const std::vector<DomainMatrix>& input, int dofCount,
                                               int extraCornerStride)
    : m_impl(std::make_unique<Impl>()), m_size(dofCount) {
  Impl& im = *m_impl;
  const int nd = static_cast<int>(input.size());
  // Classify DOFs by how many domains hold them.
  std::vector<int> holders(dofCount, 0), owner(dofCount, -1);
  for (int j = 0; j < nd; ++j)
    for (int d : input[j].dofs) {
      ++holders[d];
      if (owner[d] < 0) owner[d] = j;
    }
  im.classes.assign(dofCount, DofClass::Internal);
  std::vector<int> cornerIndex(dofCount, -1), dualIndex(dofCount, -1);
  int duplicateSeen = 0;
  for (int d = 0; d < dofCount; ++d) {
    if (holders[d] > 2) {
      im.classes[d] = DofClass::Corner;
    } else if (holders[d] == 2) {
      const bool extra = extraCornerStride > 0 && duplicateSeen++ % extraCornerStride == extraCornerStride - 1;
      im.classes[d] = extra ? DofClass::Corner : DofClass::Duplicate;
    }
    if (im.classes[d] == DofClass::Corner) {
      cornerIndex[d] = static_cast<int>(im.cornerDof.size());
      im.cornerDof.push_back(d);
    } else if (im.classes[d] == DofClass::Duplicate) {
      dualIndex[d] = im.nDual++;
    }
  }
  const int nC = static_cast<int>(im.cornerDof.size());

  // Per-domain blocks and factorisations, then their contributions to G_RR, G_RC, G_CC.
  im.domains.resize(nd);
  std::vector<std::vector<Eigen::Triplet<double>>> gRRParts(nd);
  std::vector<Eigen::MatrixXd> gRCParts(nd), gCCParts(nd);
  std::atomic<bool> allOk{true};
  tbb::parallel_for(0, nd, [&](int j) {
    Domain& dom = im.domains[j];
    const DomainMatrix& dm = input[j];
    const int n = static_cast<int>(dm.dofs.size());
    std::vector<int> rPos(n, -1), cPos(n, -1);
    for (int l = 0; l < n; ++l) {
      const int d = dm.dofs[l];
      if (im.classes[d] == DofClass::Corner) {
        cPos[l] = static_cast<int>(dom.cCorner.size());
        dom.cCorner.push_back(cornerIndex[d]);
      } else {
        rPos[l] = static_cast<int>(dom.rGlobal.size());
        dom.rGlobal.push_back(d);
        const bool own = owner[d] == j;
        dom.rTakesB.push_back(own);
        dom.rWrites.push_back(own);
        if (im.classes[d] == DofClass::Duplicate) {
          dom.dupLocal.push_back(rPos[l]);
          dom.dupDual.push_back(dualIndex[d]);
          dom.dupSign.push_back(own ? 1.0 : -1.0);
        }
      }
    }
    const int nR = static_cast<int>(dom.rGlobal.size()), nCj = static_cast<int>(dom.cCorner.size());
    std::vector<Eigen::Triplet<double>> rr, rc, cc;
    for (int col = 0; col < dm.k.outerSize(); ++col)
      for (SpMat::InnerIterator it(dm.k, col); it; ++it) {
        const int r = static_cast<int>(it.row()), c = static_cast<int>(it.col());
        if (rPos[r] >= 0 && rPos[c] >= 0) rr.emplace_back(rPos[r], rPos[c], it.value());
        else if (rPos[r] >= 0 && cPos[c] >= 0) rc.emplace_back(rPos[r], cPos[c], it.value());
        else if (cPos[r] >= 0 && cPos[c] >= 0) cc.emplace_back(cPos[r], cPos[c], it.value());
      }
    SpMat kRR(nR, nR);
    kRR.setFromTriplets(rr.begin(), rr.end());
    dom.kRC.resize(nR, nCj);
    dom.kRC.setFromTriplets(rc.begin(), rc.end());
    dom.kCC.resize(nCj, nCj);
    dom.kCC.setFromTriplets(cc.begin(), cc.end());
    if (nR == 0) {
      gCCParts[j] = Eigen::MatrixXd(dom.kCC);
      return;
    }
    dom.rhs.assign(3 * static_cast<size_t>(nR), 0.0);
    dom.work.assign(3 * static_cast<size_t>(nR), 0.0);
    if (!dom.llt.factor(kRR)) {
      allOk = false;
      return;
    }
    const int nDj = static_cast<int>(dom.dupLocal.size());
    if (nDj > 0) {
      Eigen::MatrixXd e = Eigen::MatrixXd::Zero(nR, nDj);
      for (int k = 0; k < nDj; ++k) e(dom.dupLocal[k], k) = dom.dupSign[k];
      const Eigen::MatrixXd y = dom.llt.solve(e);
      for (int a = 0; a < nDj; ++a)
        for (int b = 0; b < nDj; ++b)
          gRRParts[j].emplace_back(dom.dupDual[a], dom.dupDual[b], dom.dupSign[a] * y(dom.dupLocal[a], b));
    }
    if (nCj > 0) {
      const Eigen::MatrixXd kRCd(dom.kRC);
      const Eigen::MatrixXd yc = dom.llt.solve(kRCd);
      gCCParts[j] = Eigen::MatrixXd(dom.kCC) - kRCd.transpose() * yc;
      gRCParts[j].resize(nDj, nCj);
      for (int a = 0; a < nDj; ++a) gRCParts[j].row(a) = dom.dupSign[a] * yc.row(dom.dupLocal[a]);
    }
  });
  m_ok = allOk;
  if (!m_ok) return;

  // Assemble and factorise G_RR (sparse: dense blocks per domain), G_RC, G_CC and the corner Schur system.
  im.gRC = Eigen::MatrixXd::Zero(im.nDual, nC);
  Eigen::MatrixXd gCC = Eigen::MatrixXd::Zero(nC, nC);
  std::vector<Eigen::Triplet<double>> gRRTrip;
  for (int j = 0; j < nd; ++j) {
    const Domain& dom = im.domains[j];
    gRRTrip.insert(gRRTrip.end(), gRRParts[j].begin(), gRRParts[j].end());
    if (gCCParts[j].size() > 0)
      for (size_t a = 0; a < dom.cCorner.size(); ++a)
        for (size_t b = 0; b < dom.cCorner.size(); ++b) gCC(dom.cCorner[a], dom.cCorner[b]) += gCCParts[j](a, b);
    if (gRCParts[j].size() > 0)
      for (size_t a = 0; a < dom.dupDual.size(); ++a)
        for (size_t b = 0; b < dom.cCorner.size(); ++b) im.gRC(dom.dupDual[a], dom.cCorner[b]) += gRCParts[j](a, b);
  }
  if (im.nDual > 0) {
    SpMat gRR(im.nDual, im.nDual);
    gRR.setFromTriplets(gRRTrip.begin(), gRRTrip.end());
    // Solved alone between the domains' parallel steps: the subtrees of its elimination tree run side by side.
    if (!im.gRR.factor(gRR, CholeskySolve::SubtreeParallel)) {
      m_ok = false;
      return;
    }
    im.dual.assign(3 * static_cast<size_t>(im.nDual), 0.0);
    im.dualWork.assign(3 * static_cast<size_t>(im.nDual), 0.0);
    if (nC > 0) {
      im.w = im.gRR.solve(im.gRC);
      gCC += im.gRC.transpose() * im.w;
    }
  }
  if (nC > 0) {
    im.gCCStar.compute(gCC);
    m_ok = im.gCCStar.info() == Eigen::Success;
  }
}

DomainDecomposedSolver::~DomainDecomposedSolver() = default;

void DomainDecomposedSolver::solve(const Eigen::MatrixX3d& b, Eigen::MatrixX3d& x) const {
  if (x.rows() != m_size) x.resize(m_size, 3);
  if (!m_ok) {
    x.setZero();
    return;
  }
  const Impl& im = *m_impl;
  const int nd = static_cast<int>(im.domains.size());
  const int nC = static_cast<int>(im.cornerDof.size());

  // Step 1: y^j = K_RR^-1 b_R^j in parallel (y^j left in dom.rhs).
  tbb::parallel_for(0, nd, [&](int j) {
    const Domain& dom = im.domains[j];
    const int nR = static_cast<int>(dom.rGlobal.size());
    if (nR == 0) return;
    double* r = dom.rhs.data();
    for (int k = 0; k < nR; ++k) {
      const bool takes = dom.rTakesB[k];
      const int d = dom.rGlobal[k];
      for (int c = 0; c < 3; ++c) r[3 * k + c] = takes ? b(d, c) : 0.0;
    }
    dom.llt.solveInPlace(r, dom.work.data());
  });
  // b_R^* (into im.dual) and b_C^*.
  double* dual = im.dual.data();
  std::fill(im.dual.begin(), im.dual.end(), 0.0);
  im.bCStar.resize(nC, 3);
  for (int c = 0; c < nC; ++c) im.bCStar.row(c) = b.row(im.cornerDof[c]);
  for (int j = 0; j < nd; ++j) {
    const Domain& dom = im.domains[j];
    if (dom.rGlobal.empty()) continue;
    const double* y = dom.rhs.data();
    for (size_t k = 0; k < dom.dupLocal.size(); ++k)
      for (int c = 0; c < 3; ++c) dual[3 * dom.dupDual[k] + c] += dom.dupSign[k] * y[3 * dom.dupLocal[k] + c];
    // b_C^* -= K_RC^T y over the domain's corners.
    for (int col = 0; col < dom.kRC.outerSize(); ++col)
      for (SpMat::InnerIterator it(dom.kRC, col); it; ++it)
        for (int c = 0; c < 3; ++c) im.bCStar(dom.cCorner[col], c) -= it.value() * y[3 * it.row() + c];
  }
  // Steps 2-3: z = G_RR^-1 b_R^*, x_C (eq. 10), then lambda = z - G_RR^-1 G_RC x_C (eq. 9), left in im.dual.
  if (im.nDual > 0) im.gRR.solveInPlace(dual, im.dualWork.data());
  if (nC > 0) {
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> z(dual, im.nDual, 3);
    Eigen::MatrixX3d rhs = im.bCStar;
    if (im.nDual > 0) rhs.noalias() += im.gRC.transpose() * z;
    im.xC = im.gCCStar.solve(rhs);
    for (int c = 0; c < nC; ++c) x.row(im.cornerDof[c]) = im.xC.row(c);
    if (im.nDual > 0) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> lambda(dual, im.nDual, 3);
      lambda.noalias() -= im.w * im.xC;
    }
  }
  // Step 4: x_R^j = K_RR^-1 (b_R^j - K_RC^j x_C^j - S_D^jT lambda) (eq. 7) in parallel. dom.rhs still holds
  // K_RR^-1 b_R^j, so only the interface correction is solved: x_R^j = y^j - K_RR^-1 (K_RC x_C + S_D^T lambda).
  tbb::parallel_for(0, nd, [&](int j) {
    const Domain& dom = im.domains[j];
    const int nR = static_cast<int>(dom.rGlobal.size());
    if (nR == 0) return;
    // y^j goes to x first; the correction right-hand side is then built in its place.
    double* y = dom.rhs.data();
    for (int k = 0; k < nR; ++k)
      if (dom.rWrites[k])
        for (int c = 0; c < 3; ++c) x(dom.rGlobal[k], c) = y[3 * k + c];
    std::fill(dom.rhs.begin(), dom.rhs.end(), 0.0);
    double* r = dom.rhs.data();
    for (int col = 0; col < dom.kRC.outerSize(); ++col)
      for (SpMat::InnerIterator it(dom.kRC, col); it; ++it)
        for (int c = 0; c < 3; ++c) r[3 * it.row() + c] += it.value() * im.xC(dom.cCorner[col], c);
    for (size_t k = 0; k < dom.dupLocal.size(); ++k)
      for (int c = 0; c < 3; ++c) r[3 * dom.dupLocal[k] + c] += dom.dupSign[k] * dual[3 * dom.dupDual[k] + c];
    dom.llt.solveInPlace(r, dom.work.data());
    for (int k = 0; k < nR; ++k)
      if (dom.rWrites[k])
        for (int c = 0; c < 3; ++c) x(dom.rGlobal[k], c) -= r[3 * k + c];
  });
}

int DomainDecomposedSolver::domainCount() const {
  int n = 0;
  for (const Domain& d : m_impl->domains) n += !d.rGlobal.empty() || !d.cCorner.empty();
  return n;
}
int DomainDecomposedSolver::cornerCount() const { return static_cast<int>(m_impl->cornerDof.size()); }
int DomainDecomposedSolver::duplicateCount() const { return m_impl->nDual; }
int DomainDecomposedSolver::maxRemainder() const {
  size_t m = 0;
  for (const Domain& d : m_impl->domains) m = std::max(m, d.rGlobal.size());
  return static_cast<int>(m);
}
const std::vector<DofClass>& DomainDecomposedSolver::dofClasses() const { return m_impl->classes; }

}  // namespace drape::pd
