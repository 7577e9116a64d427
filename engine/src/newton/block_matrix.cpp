#include "drape/newton/block_matrix.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "drape/newton/dof_ordering.h"

namespace drape::newton {

BlockMatrix::BlockMatrix(int numBlocks, const std::vector<std::pair<int, int>>& couplings, bool reorder) {
  build(numBlocks, couplings, reorder);
}

void BlockMatrix::build(int numBlocks, const std::vector<std::pair<int, int>>& couplings, bool reorder) {
  static std::atomic<long> nextPatternId{0};
  m_patternId = nextPatternId.fetch_add(1);
  m_numBlocks = numBlocks;
  m_order.clear();
  m_position.clear();
  std::vector<std::vector<int>> rows = adjacencyLists(numBlocks, couplings);
  if (reorder) {
    m_order = reverseCuthillMcKee(rows);
    m_position = invertPermutation(m_order);
    std::vector<std::vector<int>> permuted(numBlocks);
    for (int i = 0; i < numBlocks; ++i) {
      auto& r = permuted[m_position[i]];
      r.reserve(rows[i].size() + 1);
      for (int j : rows[i]) r.push_back(m_position[j]);
    }
    rows.swap(permuted);
  }
  for (int i = 0; i < numBlocks; ++i) rows[i].push_back(i);
  m_rowStart.assign(numBlocks + 1, 0);
  m_cols.clear();
  m_diag.assign(numBlocks, -1);
  for (int i = 0; i < numBlocks; ++i) {
    auto& r = rows[i];
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    for (int c : r) {
      if (c == i) m_diag[i] = static_cast<int>(m_cols.size());
      m_cols.push_back(c);
    }
    m_rowStart[i + 1] = static_cast<int>(m_cols.size());
  }
  m_blocks.assign(m_cols.size(), Eigen::Matrix3d::Zero());
  m_dynamic.clear();
}

void BlockMatrix::setZero() {
  for (auto& b : m_blocks) b.setZero();
  m_dynamic.clear();
}

void BlockMatrix::setStaticValues(const std::vector<Eigen::Matrix3d>& values) {
  if (values.size() != m_blocks.size())
    throw std::invalid_argument("block matrix: " + std::to_string(values.size()) + " saved blocks for a pattern of " +
                                std::to_string(m_blocks.size()));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, values.size(), 16384), [&](const tbb::blocked_range<size_t>& r) {
    std::copy(values.begin() + r.begin(), values.begin() + r.end(), m_blocks.begin() + r.begin());
  });
  m_dynamic.clear();
}

int BlockMatrix::bandwidth() const {
  int bw = 0;
  for (int r = 0; r < m_numBlocks; ++r)
    for (int k = m_rowStart[r]; k < m_rowStart[r + 1]; ++k) bw = std::max(bw, std::abs(m_cols[k] - r));
  return bw;
}

int BlockMatrix::findBlock(int i, int j) const {
  if (i < 0 || j < 0 || i >= m_numBlocks || j >= m_numBlocks) return -1;
  i = internalIndex(i);
  j = internalIndex(j);
  auto begin = m_cols.begin() + m_rowStart[i];
  auto end = m_cols.begin() + m_rowStart[i + 1];
  auto it = std::lower_bound(begin, end, j);
  if (it == end || *it != j) return -1;
  return static_cast<int>(it - m_cols.begin());
}

void BlockMatrix::addBlock(int i, int j, const Eigen::Matrix3d& b) {
  int k = findBlock(i, j);
  if (k < 0) {
    addDynamicBlock(i, j, b);
    return;
  }
  m_blocks[k] += b;
  if (i != j) m_blocks[findBlock(j, i)] += b.transpose();
}

void BlockMatrix::addDynamicBlock(int i, int j, const Eigen::Matrix3d& b) {
  std::lock_guard<std::mutex> lock(m_dynamicMutex);
  m_dynamic.push_back({i, j, b});
}

Eigen::Matrix3d BlockMatrix::fullDiagonalBlock(int i) const {
  Eigen::Matrix3d d = diagonalBlock(i);
  for (const auto& e : m_dynamic)
    if (e.i == i && e.j == i) d += e.block;
  return d;
}

void BlockMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  assert(x.size() == size());
  y.resize(size());
  // Vertex order: row i is storage row internalIndex(i), column c holds vertex originalIndex(c).
  tbb::parallel_for(tbb::blocked_range<int>(0, m_numBlocks, 256), [&](const tbb::blocked_range<int>& range) {
    for (int i = range.begin(); i < range.end(); ++i) {
      const int r = internalIndex(i);
      Eigen::Vector3d acc = Eigen::Vector3d::Zero();
      for (int k = m_rowStart[r]; k < m_rowStart[r + 1]; ++k)
        acc += m_blocks[k] * x.segment<3>(3 * originalIndex(m_cols[k]));
      y.segment<3>(3 * i) = acc;
    }
  });
  // Dynamic (contact) part: few entries, applied serially (section 6.1: SpMV = static + dynamic).
  for (const auto& e : m_dynamic) {
    y.segment<3>(3 * e.i) += e.block * x.segment<3>(3 * e.j);
    if (e.i != e.j) y.segment<3>(3 * e.j) += e.block.transpose() * x.segment<3>(3 * e.i);
  }
}

Eigen::VectorXd BlockMatrix::operator*(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y;
  multiply(x, y);
  return y;
}

Eigen::SparseMatrix<double> BlockMatrix::toSparse() const {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(9 * (m_blocks.size() + 2 * m_dynamic.size()));
  auto put = [&t](int i, int j, const Eigen::Matrix3d& b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t.emplace_back(3 * i + r, 3 * j + c, b(r, c));
  };
  for (int r = 0; r < m_numBlocks; ++r)
    for (int k = m_rowStart[r]; k < m_rowStart[r + 1]; ++k) put(originalIndex(r), originalIndex(m_cols[k]), m_blocks[k]);
  for (const auto& e : m_dynamic) {
    put(e.i, e.j, e.block);
    if (e.i != e.j) put(e.j, e.i, e.block.transpose());
  }
  Eigen::SparseMatrix<double> s(size(), size());
  s.setFromTriplets(t.begin(), t.end());
  return s;
}

}  // namespace drape::newton
