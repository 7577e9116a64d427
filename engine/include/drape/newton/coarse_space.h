// Coarse level of the two-level PCG preconditioner (not in the paper; solver.cg.coarse_aggregate): the block
// rows are grouped into aggregates of about k connected vertices, P (3|V| x 3m) maps each aggregate's three
// translations to its vertices, and the preconditioner adds P (P^T A P)^-1 P^T r to block-Jacobi's z (additive
// two-level Schwarz). Block-Jacobi alone leaves the long-wavelength stretch modes of a stiff fabric to the CG
// iterations; the coarse solve removes them (docs/BENCHMARKS.md, "Table 7").
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <map>
#include <memory>
#include <vector>

#include "drape/newton/block_matrix.h"

namespace drape::newton {

class CoarseSpace {
 public:
  // Aggregates of about `size` (>= 2) block rows of a's static pattern, grown breadth first in storage order.
  CoarseSpace(const BlockMatrix& a, int size);
  ~CoarseSpace();

  int numAggregates() const { return m_numAggregates; }
  // Aggregate of each storage row of the matrix it was built for.
  const std::vector<int>& aggregateOfRow() const { return m_aggregate; }

  // P^T A P from a's static blocks and its dynamic (contact) entries, factorised by CHOLMOD (the pattern is
  // analysed once). A dynamic entry between aggregates the static pattern does not join (a contact between
  // distant parts of the cloth) adds only its diagonal parts. False when that matrix is not positive definite;
  // ready() then stays false until a later factorisation succeeds.
  bool factorize(const BlockMatrix& a);
  bool ready() const { return m_ready; }

  // e = (P^T A P)^-1 rc, both 3m (aggregate-major x, y, z).
  void solve(const Eigen::VectorXd& rc, Eigen::VectorXd& e) const;

 private:
  struct Factor;
  int m_numAggregates = 0;
  std::vector<int> m_aggregate;   // per storage row
  std::vector<int> m_blockSlot;   // per static block: coarse block index
  std::vector<int> m_slotOffset;  // per coarse block: offset of its (0, 0) entry in each of its 3 columns, x3
  std::map<std::pair<int, int>, int> m_slotOf;  // coarse block index of an aggregate pair
  Eigen::SparseMatrix<double> m_coarse;  // 3m x 3m, fixed pattern (full: both triangles)
  std::unique_ptr<Factor> m_factor;
  bool m_ready = false;
};

}  // namespace drape::newton
