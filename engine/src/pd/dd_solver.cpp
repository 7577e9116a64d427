#include "drape/pd/dd_solver.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <tbb/parallel_for.h>

namespace drape::pd {
namespace {

using SpMat = Eigen::SparseMatrix<double>;
using Cholmod = Eigen::CholmodDecomposition<SpMat, Eigen::Lower>;

struct Domain {
  std::vector<int> rGlobal;       // local R -> global DOF
  std::vector<std::uint8_t> rTakesB;  // internal, or duplicate owned by this domain: b goes here
  std::vector<std::uint8_t> rWrites;  // this domain writes x of the DOF
  std::vector<int> cCorner;       // local C -> corner index
  std::vector<int> dupLocal;      // duplicates: local R index
  std::vector<int> dupDual;       //             index into lambda
  std::vector<double> dupSign;    //             +1 owner (lower domain), -1 other
  SpMat kRC, kCC;
  std::unique_ptr<Cholmod> llt;
};

}  // namespace

struct DomainDecomposedSolver::Impl {
  std::vector<Domain> domains;
  std::vector<DofClass> classes;
  std::vector<int> cornerDof;     // corner index -> DOF
  int nDual = 0;
  Cholmod gRR;
  Eigen::MatrixXd gRC;            // nDual x nC
  Eigen::MatrixXd w;              // G_RR^-1 G_RC
  Eigen::LLT<Eigen::MatrixXd> gCCStar;
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
    dom.llt = std::make_unique<Cholmod>();
    dom.llt->compute(kRR);
    if (dom.llt->info() != Eigen::Success) {
      allOk = false;
      return;
    }
    const int nDj = static_cast<int>(dom.dupLocal.size());
    if (nDj > 0) {
      Eigen::MatrixXd e = Eigen::MatrixXd::Zero(nR, nDj);
      for (int k = 0; k < nDj; ++k) e(dom.dupLocal[k], k) = dom.dupSign[k];
      const Eigen::MatrixXd y = dom.llt->solve(e);
      for (int a = 0; a < nDj; ++a)
        for (int b = 0; b < nDj; ++b)
          gRRParts[j].emplace_back(dom.dupDual[a], dom.dupDual[b], dom.dupSign[a] * y(dom.dupLocal[a], b));
    }
    if (nCj > 0) {
      const Eigen::MatrixXd kRCd(dom.kRC);
      const Eigen::MatrixXd yc = dom.llt->solve(kRCd);
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
    im.gRR.compute(gRR);
    if (im.gRR.info() != Eigen::Success) {
      m_ok = false;
      return;
    }
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
  x.setZero(m_size, 3);
  if (!m_ok) return;
  const Impl& im = *m_impl;
  const int nd = static_cast<int>(im.domains.size());
  const int nC = static_cast<int>(im.cornerDof.size());

  // Step 1: y^j = K_RR^-1 b_R^j in parallel.
  std::vector<Eigen::MatrixX3d> bR(nd), y(nd);
  tbb::parallel_for(0, nd, [&](int j) {
    const Domain& dom = im.domains[j];
    const int nR = static_cast<int>(dom.rGlobal.size());
    if (nR == 0) return;
    bR[j].setZero(nR, 3);
    for (int r = 0; r < nR; ++r)
      if (dom.rTakesB[r]) bR[j].row(r) = b.row(dom.rGlobal[r]);
    y[j] = dom.llt->solve(bR[j]);
  });
  // b_R^* and b_C^*.
  Eigen::MatrixX3d bRStar = Eigen::MatrixX3d::Zero(im.nDual, 3);
  Eigen::MatrixX3d bCStar(nC, 3);
  for (int c = 0; c < nC; ++c) bCStar.row(c) = b.row(im.cornerDof[c]);
  for (int j = 0; j < nd; ++j) {
    const Domain& dom = im.domains[j];
    if (dom.rGlobal.empty()) continue;
    for (size_t k = 0; k < dom.dupLocal.size(); ++k) bRStar.row(dom.dupDual[k]) += dom.dupSign[k] * y[j].row(dom.dupLocal[k]);
    if (!dom.cCorner.empty()) {
      const Eigen::MatrixX3d t = dom.kRC.transpose() * y[j];
      for (size_t c = 0; c < dom.cCorner.size(); ++c) bCStar.row(dom.cCorner[c]) -= t.row(static_cast<int>(c));
    }
  }
  // Steps 2-3: x_C (eq. 10), then lambda (eq. 9).
  Eigen::MatrixX3d z, xC, lambda;
  if (im.nDual > 0) z = im.gRR.solve(bRStar);
  if (nC > 0) {
    Eigen::MatrixX3d rhs = bCStar;
    if (im.nDual > 0) rhs += im.gRC.transpose() * z;
    xC = im.gCCStar.solve(rhs);
    for (int c = 0; c < nC; ++c) x.row(im.cornerDof[c]) = xC.row(c);
  }
  if (im.nDual > 0) lambda = nC > 0 ? Eigen::MatrixX3d(z - im.w * xC) : z;
  // Step 4: x_R^j (eq. 7) in parallel.
  tbb::parallel_for(0, nd, [&](int j) {
    const Domain& dom = im.domains[j];
    if (dom.rGlobal.empty()) return;
    Eigen::MatrixX3d r = bR[j];
    if (!dom.cCorner.empty()) {
      Eigen::MatrixX3d xCj(dom.cCorner.size(), 3);
      for (size_t c = 0; c < dom.cCorner.size(); ++c) xCj.row(static_cast<int>(c)) = xC.row(dom.cCorner[c]);
      r -= dom.kRC * xCj;
    }
    for (size_t k = 0; k < dom.dupLocal.size(); ++k) r.row(dom.dupLocal[k]) -= dom.dupSign[k] * lambda.row(dom.dupDual[k]);
    const Eigen::MatrixX3d xR = dom.llt->solve(r);
    for (size_t l = 0; l < dom.rGlobal.size(); ++l)
      if (dom.rWrites[l]) x.row(dom.rGlobal[l]) = xR.row(static_cast<int>(l));
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
