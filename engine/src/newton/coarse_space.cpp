#include "drape/newton/coarse_space.h"

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <stdexcept>

namespace drape::newton {

struct CoarseSpace::Factor {
  Eigen::CholmodSimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  bool analysed = false;
};

CoarseSpace::CoarseSpace(const BlockMatrix& a, int size) : m_factor(std::make_unique<Factor>()) {
  if (size < 2) throw std::invalid_argument("coarse space: aggregates need at least 2 vertices");
  const int n = a.numBlocks();
  const int* rowStart = a.rowStarts();
  const int* cols = a.colIndices();
  // Breadth-first aggregates in storage order: each unassigned row seeds one and takes unassigned neighbours
  // until it has `size` rows.
  m_aggregate.assign(n, -1);
  std::vector<int> queue;
  for (int seed = 0; seed < n; ++seed) {
    if (m_aggregate[seed] >= 0) continue;
    const int id = m_numAggregates++;
    queue.assign(1, seed);
    m_aggregate[seed] = id;
    int count = 1;
    for (size_t q = 0; q < queue.size() && count < size; ++q)
      for (int k = rowStart[queue[q]]; k < rowStart[queue[q] + 1] && count < size; ++k)
        if (m_aggregate[cols[k]] < 0) {
          m_aggregate[cols[k]] = id;
          queue.push_back(cols[k]);
          ++count;
        }
  }
  // Coarse block pattern: aggregate pairs joined by a static block.
  std::map<std::pair<int, int>, int>& slotOf = m_slotOf;
  std::vector<std::pair<int, int>> pairs;
  m_blockSlot.resize(rowStart[n]);
  for (int r = 0; r < n; ++r)
    for (int k = rowStart[r]; k < rowStart[r + 1]; ++k) {
      const std::pair<int, int> key{m_aggregate[r], m_aggregate[cols[k]]};
      auto [it, inserted] = slotOf.emplace(key, static_cast<int>(pairs.size()));
      if (inserted) pairs.push_back(key);
      m_blockSlot[k] = it->second;
    }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(9 * pairs.size());
  for (const auto& [i, j] : pairs)
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) triplets.emplace_back(3 * i + r, 3 * j + c, 1.0);
  const int m3 = 3 * m_numAggregates;
  m_coarse.resize(m3, m3);
  m_coarse.setFromTriplets(triplets.begin(), triplets.end());
  m_coarse.makeCompressed();
  // Offset of entry (3 i, 3 j + c) in the value array: the block's three rows are consecutive in each column.
  m_slotOffset.resize(3 * pairs.size());
  for (size_t s = 0; s < pairs.size(); ++s) {
    const auto [i, j] = pairs[s];
    for (int c = 0; c < 3; ++c) {
      const int col = 3 * j + c;
      const int* begin = m_coarse.innerIndexPtr() + m_coarse.outerIndexPtr()[col];
      const int* end = m_coarse.innerIndexPtr() + m_coarse.outerIndexPtr()[col + 1];
      m_slotOffset[3 * s + c] = static_cast<int>(std::lower_bound(begin, end, 3 * i) - m_coarse.innerIndexPtr());
    }
  }
}

CoarseSpace::~CoarseSpace() = default;

bool CoarseSpace::factorize(const BlockMatrix& a) {
  m_ready = false;
  double* values = m_coarse.valuePtr();
  std::fill(values, values + m_coarse.nonZeros(), 0.0);
  auto add = [&](int s, const Eigen::Matrix3d& b) {
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) values[m_slotOffset[3 * s + c] + r] += b(r, c);
  };
  const auto& blocks = a.blocks();
  for (size_t k = 0; k < blocks.size(); ++k) add(m_blockSlot[k], blocks[k]);
  // A dynamic entry (i, j) stands for the blocks (i, j) and (j, i) = its transpose (i != j).
  for (const auto& e : a.dynamicEntries()) {
    const int ai = m_aggregate[a.internalIndex(e.i)], aj = m_aggregate[a.internalIndex(e.j)];
    if (e.i == e.j) {
      add(m_slotOf.at({ai, ai}), e.block);
      continue;
    }
    const auto ij = m_slotOf.find({ai, aj});
    if (ij == m_slotOf.end()) continue;  // aggregates not joined by the static pattern: see the header
    add(ij->second, e.block);
    add(m_slotOf.at({aj, ai}), e.block.transpose());
  }
  if (!m_factor->analysed) {
    // A fill-reducing ordering, the better of minimum degree and nested dissection. CHOLMOD's default strategy kept
    // the rows' own (RCM-derived) order here, whose factor has far more entries and costs far more flops than nested
    // dissection's.
    cholmod_common& common = m_factor->llt.cholmod();
    common.nmethods = 2;
    common.method[0].ordering = CHOLMOD_AMD;
    common.method[1].ordering = CHOLMOD_NESDIS;
    m_factor->llt.analyzePattern(m_coarse);
    m_factor->analysed = true;
  }
  m_factor->llt.factorize(m_coarse);
  m_ready = m_factor->llt.info() == Eigen::Success;
  return m_ready;
}

void CoarseSpace::solve(const Eigen::VectorXd& rc, Eigen::VectorXd& e) const { e = m_factor->llt.solve(rc); }

}  // namespace drape::newton
