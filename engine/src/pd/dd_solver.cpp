#include "drape/pd/dd_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <type_traits>
#include <tbb/parallel_for.h>

#include "drape/pd/sparse_cholesky.h"

namespace drape::pd {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

// Local R indices follow the order of the domain's factor once it is built (orderLikeFactor). Its interface is
// the duplicates and the rows of K_RC: what lambda and x_C act on, and where y^j = K_RR^-1 b_R^j is read.
struct Domain {
  std::vector<int> rGlobal;       // local R -> global DOF
  std::vector<std::uint8_t> rTakesB;  // internal, or duplicate owned by this domain: b goes here
  std::vector<std::uint8_t> rWrites;  // this domain writes x of the DOF
  std::vector<int> cCorner;       // local C -> corner index
  std::vector<int> dupLocal;      // duplicates: local R index
  std::vector<int> dupDual;       //             index into lambda
  std::vector<double> dupSign;    //             +1 owner (lower domain), -1 other
  SpMat kRC, kCC;
  SparseCholesky llt;             // K_RR^j, with the interface set
  // Scratch of solve(), sized once (N_R^j x 3 row-major): L^-1 b_R^j and then x_R^j; on the columns the interface
  // reaches, y^j and then L^-1 of the interface's correction.
  mutable std::vector<double> forward, reached;
};

// Renumbers the domain's R DOFs into the order of its factor, so that solves need no permutation.
void orderLikeFactor(Domain& dom) {
  const std::vector<int>& perm = dom.llt.permutation();
  const int nR = static_cast<int>(perm.size());
  std::vector<int> position(nR);
  for (int k = 0; k < nR; ++k) position[perm[k]] = k;
  auto permuted = [&](const auto& v) {
    std::decay_t<decltype(v)> out(v.size());
    for (int k = 0; k < nR; ++k) out[k] = v[perm[k]];
    return out;
  };
  dom.rGlobal = permuted(dom.rGlobal);
  dom.rTakesB = permuted(dom.rTakesB);
  dom.rWrites = permuted(dom.rWrites);
  for (int& l : dom.dupLocal) l = position[l];
  std::vector<Eigen::Triplet<double>> rc;
  for (int col = 0; col < dom.kRC.outerSize(); ++col)
    for (SpMat::InnerIterator it(dom.kRC, col); it; ++it) rc.emplace_back(position[it.row()], col, it.value());
  dom.kRC.setFromTriplets(rc.begin(), rc.end());
}

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
    dom.forward.assign(3 * static_cast<size_t>(nR), 0.0);
    dom.reached.assign(3 * static_cast<size_t>(nR), 0.0);
    std::vector<int> interface = dom.dupLocal;
    for (int col = 0; col < dom.kRC.outerSize(); ++col)
      for (SpMat::InnerIterator it(dom.kRC, col); it; ++it) interface.push_back(static_cast<int>(it.row()));
    std::sort(interface.begin(), interface.end());
    interface.erase(std::unique(interface.begin(), interface.end()), interface.end());
    if (!dom.llt.factor(kRR)) {
      allOk = false;
      return;
    }
    dom.llt.setInterface(interface);
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
    orderLikeFactor(dom);
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

  // Step 1, per domain in parallel: f^j = L^-1 b_R^j (the domain's R DOFs are numbered like its factor), and
  // y^j = K_RR^-1 b_R^j where the interface reaches, from that part of the backward pass (left in dom.reached).
  tbb::parallel_for(0, nd, [&](int j) {
    const Domain& dom = im.domains[j];
    const int nR = static_cast<int>(dom.rGlobal.size());
    if (nR == 0) return;
    double* f = dom.forward.data();
    for (int k = 0; k < nR; ++k) {
      const bool takes = dom.rTakesB[k];
      const int d = dom.rGlobal[k];
      for (int c = 0; c < 3; ++c) f[3 * k + c] = takes ? b(d, c) : 0.0;
    }
    dom.llt.forward(f);
    double* y = dom.reached.data();
    for (int k : dom.llt.reachedColumns())
      for (int c = 0; c < 3; ++c) y[3 * k + c] = f[3 * k + c];
    dom.llt.backwardOverInterface(y);
  });
  // b_R^* (into im.dual) and b_C^*.
  double* dual = im.dual.data();
  std::fill(im.dual.begin(), im.dual.end(), 0.0);
  im.bCStar.resize(nC, 3);
  for (int c = 0; c < nC; ++c) im.bCStar.row(c) = b.row(im.cornerDof[c]);
  for (int j = 0; j < nd; ++j) {
    const Domain& dom = im.domains[j];
    if (dom.rGlobal.empty()) continue;
    const double* y = dom.reached.data();
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
  // Step 4: x_R^j = K_RR^-1 (b_R^j - K_RC^j x_C^j - S_D^jT lambda) (eq. 7) in parallel. The correction
  // K_RC x_C + S_D^T lambda lives on the interface, so its forward pass reads only the columns the interface
  // reaches; subtracted from f^j, one backward pass gives x_R^j. Per solve, each domain reads its factor twice and
  // the reached columns (63 % of it at 100k vertices, D = 16) twice more.
  tbb::parallel_for(0, nd, [&](int j) {
    const Domain& dom = im.domains[j];
    const int nR = static_cast<int>(dom.rGlobal.size());
    if (nR == 0) return;
    const std::vector<int>& reachedColumns = dom.llt.reachedColumns();
    double* t = dom.reached.data();
    for (int k : reachedColumns)
      for (int c = 0; c < 3; ++c) t[3 * k + c] = 0.0;
    for (int col = 0; col < dom.kRC.outerSize(); ++col)
      for (SpMat::InnerIterator it(dom.kRC, col); it; ++it)
        for (int c = 0; c < 3; ++c) t[3 * it.row() + c] += it.value() * im.xC(dom.cCorner[col], c);
    for (size_t k = 0; k < dom.dupLocal.size(); ++k)
      for (int c = 0; c < 3; ++c) t[3 * dom.dupLocal[k] + c] += dom.dupSign[k] * dual[3 * dom.dupDual[k] + c];
    dom.llt.forwardOverInterface(t);
    double* f = dom.forward.data();
    for (int k : reachedColumns)
      for (int c = 0; c < 3; ++c) f[3 * k + c] -= t[3 * k + c];
    dom.llt.backward(f);
    for (int k = 0; k < nR; ++k)
      if (dom.rWrites[k])
        for (int c = 0; c < 3; ++c) x(dom.rGlobal[k], c) = f[3 * k + c];
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
