#include "drape/newton/coupled_groups.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "drape/core/disjoint_sets.h"

namespace drape::newton {

CoupledGroups::CoupledGroups(const BlockMatrix& a, double threshold, int maxSize) {
  maxSize = std::clamp(maxSize, 2, kMaxSize);
  const int n = a.numBlocks();
  const int* rowStart = a.rowStarts();
  const int* cols = a.colIndices();
  const std::vector<Eigen::Matrix3d>& blocks = a.blocks();
  std::vector<double> trace(n);
  for (int r = 0; r < n; ++r) trace[r] = a.diagonalBlock(a.originalIndex(r)).trace();
  // Rows joined coupling by coupling, in storage order, while the group stays within maxSize.
  std::vector<int> parent(n), size(n, 1);
  std::iota(parent.begin(), parent.end(), 0);
  const double t2 = threshold * threshold;
  for (int r = 0; r < n; ++r)
    for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
      const int c = cols[k];
      if (c <= r) continue;
      const double b = blocks[k].trace();
      if (!(b * b >= t2 * trace[r] * trace[c]) || trace[r] <= 0.0 || trace[c] <= 0.0) continue;
      int rr = findRoot(parent, r), rc = findRoot(parent, c);
      if (rr == rc || size[rr] + size[rc] > maxSize) continue;
      if (size[rr] < size[rc]) std::swap(rr, rc);
      parent[rc] = rr;
      size[rr] += size[rc];
    }
  // Groups of two or more, numbered by their first row; rows ascending within a group.
  m_groupOf.assign(n, -1);
  m_slot.assign(n, -1);
  std::vector<int> groupOfRoot(n, -1), fill;
  for (int r = 0; r < n; ++r) {
    const int root = findRoot(parent, r);
    if (size[root] < 2) continue;
    if (groupOfRoot[root] < 0) {
      groupOfRoot[root] = static_cast<int>(m_start.size()) - 1;
      m_start.push_back(m_start.back() + size[root]);
      fill.push_back(m_start[m_start.size() - 2]);
    }
    const int g = groupOfRoot[root];
    m_groupOf[r] = g;
    m_slot[r] = fill[g] - m_start[g];
    ++fill[g];
  }
  m_rows.resize(m_start.back());
  for (int r = 0; r < n; ++r)
    if (m_groupOf[r] >= 0) m_rows[m_start[m_groupOf[r]] + m_slot[r]] = r;
  m_inverseAt.resize(count());
  int at = 0;
  for (int g = 0; g < count(); ++g) {
    m_inverseAt[g] = at;
    const int m = m_start[g + 1] - m_start[g];
    at += 9 * m * m;
  }
  m_inverse.resize(at);
  refresh(a);
}

void CoupledGroups::refresh(const BlockMatrix& a) {
  const int* rowStart = a.rowStarts();
  const int* cols = a.colIndices();
  const std::vector<Eigen::Matrix3d>& blocks = a.blocks();
  auto submatrix = [this](int g) {
    const int m = m_start[g + 1] - m_start[g];
    return Eigen::Map<Eigen::MatrixXd>(m_inverse.data() + m_inverseAt[g], 3 * m, 3 * m);
  };
  // Each group's submatrix in its own slot: the static blocks between its rows, then the dynamic entries between
  // them (contact on a grouped row, cloth-cloth contact between two of its rows).
  for (int g = 0; g < count(); ++g) {
    Eigen::Map<Eigen::MatrixXd> sub = submatrix(g);
    sub.setZero();
    for (int s = 0; s < sub.rows() / 3; ++s) {
      const int r = m_rows[m_start[g] + s];
      for (int k = rowStart[r]; k < rowStart[r + 1]; ++k)
        if (m_groupOf[cols[k]] == g) sub.block<3, 3>(3 * s, 3 * m_slot[cols[k]]) = blocks[k];
    }
  }
  for (const auto& e : a.dynamicEntries()) {
    const int i = a.internalIndex(e.i), j = a.internalIndex(e.j), g = m_groupOf[i];
    if (g < 0 || m_groupOf[j] != g) continue;
    Eigen::Map<Eigen::MatrixXd> sub = submatrix(g);
    sub.block<3, 3>(3 * m_slot[i], 3 * m_slot[j]) += e.block;
    if (i != j) sub.block<3, 3>(3 * m_slot[j], 3 * m_slot[i]) += e.block.transpose();
  }
  // Inverted in place by Cholesky; pairs, nearly every group, in fixed size. A group whose submatrix is not positive
  // definite takes block-Jacobi's blocks (the inverses of its diagonal blocks).
  Eigen::MatrixXd sub;
  for (int g = 0; g < count(); ++g) {
    Eigen::Map<Eigen::MatrixXd> inverse = submatrix(g);
    sub = inverse;
    bool good;
    if (sub.rows() == 6) {
      const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(sub);
      good = llt.info() == Eigen::Success;
      if (good) inverse = llt.solve(Eigen::Matrix<double, 6, 6>::Identity());
    } else {
      const Eigen::LLT<Eigen::MatrixXd> llt(sub);
      good = llt.info() == Eigen::Success;
      if (good) inverse = llt.solve(Eigen::MatrixXd::Identity(sub.rows(), sub.cols()));
    }
    if (good && inverse.allFinite()) continue;
    inverse.setZero();
    for (int s = 0; s < sub.rows() / 3; ++s) {
      Eigen::Matrix3d di = sub.block<3, 3>(3 * s, 3 * s).inverse();
      if (!di.allFinite()) di.setIdentity();
      inverse.block<3, 3>(3 * s, 3 * s) = di;
    }
  }
}

template <typename S>
double CoupledGroups::apply(const Eigen::Matrix<S, Eigen::Dynamic, 1>& r,
                            Eigen::Matrix<S, Eigen::Dynamic, 1>& z) const {
  double change = 0.0;
  Eigen::Matrix<double, 3 * kMaxSize, 1> rg, zg;
  for (int g = 0; g < count(); ++g) {
    const int m = m_start[g + 1] - m_start[g];
    const int* rows = m_rows.data() + m_start[g];
    for (int s = 0; s < m; ++s) {
      rg.segment<3>(3 * s) = r.template segment<3>(3 * rows[s]).template cast<double>();
      change -= rg.segment<3>(3 * s).dot(z.template segment<3>(3 * rows[s]).template cast<double>());
    }
    const double* inverse = m_inverse.data() + m_inverseAt[g];
    if (m == 2)
      zg.head<6>().noalias() = Eigen::Map<const Eigen::Matrix<double, 6, 6>>(inverse) * rg.head<6>();
    else
      zg.head(3 * m).noalias() = Eigen::Map<const Eigen::MatrixXd>(inverse, 3 * m, 3 * m) * rg.head(3 * m);
    change += rg.head(3 * m).dot(zg.head(3 * m));
    for (int s = 0; s < m; ++s) z.template segment<3>(3 * rows[s]) = zg.segment<3>(3 * s).template cast<S>();
  }
  return change;
}

template double CoupledGroups::apply<float>(const Eigen::VectorXf&, Eigen::VectorXf&) const;
template double CoupledGroups::apply<double>(const Eigen::VectorXd&, Eigen::VectorXd&) const;

}  // namespace drape::newton
