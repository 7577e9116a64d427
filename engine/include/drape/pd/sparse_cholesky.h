#pragma once
// A sparse Cholesky factor P A P^T = L L^T kept as plain compressed columns, solved for three right-hand sides at
// once (the x, y, z coordinates of the Projective Dynamics global step, pd-dd eq. 3). CHOLMOD computes the
// ordering and the simplicial factor once; the solves are our own loops so that each non-zero of L is read once
// in the forward and once in the backward pass for all three columns, with no allocation (the per-iteration
// bandwidth floor of the global step; see docs/BENCHMARKS.md, "L-G iteration at 100k vertices").
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "drape/pd/subtree_groups.h"

namespace drape::pd {

// Sequential: CHOLMOD's fill-reducing ordering, one thread per solve (the domains' own factors, solved side by side).
// SubtreeParallel: each solve runs the independent subtrees of the elimination tree on the threads of the calling
// arena, in groups of about equal work, and the separators above them on one thread (the coarse dual system G_RR
// of the domain-decomposed solve, which is solved alone). Of minimum degree (AMD) and nested dissection (METIS),
// the ordering with the shorter such solve is kept.
enum class CholeskySolve { Sequential, SubtreeParallel };

class SparseCholesky {
 public:
  SparseCholesky() = default;
  // a: symmetric positive definite n x n (both triangles stored or only the lower one; the lower one is read).
  // Returns false (and ok() stays false) when a is not numerically positive definite.
  bool factor(const Eigen::SparseMatrix<double>& a, CholeskySolve mode = CholeskySolve::Sequential);
  bool ok() const { return m_ok; }
  int size() const { return m_n; }
  long nonZeros() const { return m_nonZeros; }  // non-zeros of L
  int subtreeGroups() const { return static_cast<int>(m_groupRows.size()); }  // 0: sequential solves

  // In place: x (n x 3, row-major: x[3 i + c]) <- A^-1 x. work: 3 n doubles of scratch, overwritten.
  void solveInPlace(double* x, double* work) const;
  // Columns of b (n x k, any k) solved three at a time; returns A^-1 b. For setup, not per iteration.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const;

  // Sequential factors only. The passes in the factor's order (w: n x 3 row-major, w[3 k + c] for row k of
  // P A P^T): w <- L^-1 w and w <- L^-T w.
  const std::vector<int>& permutation() const { return m_perm; }  // row k of P A P^T is row permutation()[k] of A
  void forward(double* w) const;
  void backward(double* w) const;
  // An interface: rows of A (setInterface) and their ancestors in the elimination tree, the columns a right-hand
  // side on the interface reaches (Gilbert-Peierls). forwardOverInterface is the forward pass of a w that is zero
  // off the interface's rows; backwardOverInterface makes w exact on the reached rows, from a forward result, and
  // leaves the others as they were. Both read only the reached columns of L (the domain-decomposed solve's
  // interface; docs/ENGINE.md, pd/sparse_cholesky.h).
  void setInterface(const std::vector<int>& rows);
  void forwardOverInterface(double* w) const;
  void backwardOverInterface(double* w) const;
  const std::vector<int>& reachedColumns() const { return m_reached; }  // ascending
  long interfaceNonZeros() const;  // non-zeros of L in the reached columns

 private:
  bool factorWith(const Eigen::SparseMatrix<double>& a, int cholmodOrdering);  // < 0: CHOLMOD's choice
  SubtreeGroups planSubtrees() const;  // of the column factor, for the threads of the calling arena
  void useSubtrees(SubtreeGroups plan);
  void solveSequential(double* w) const;       // w: permuted right-hand side in, solution out
  void solveSubtreeParallel(double* w) const;  // the same, by groups of subtrees

  int m_n = 0;
  long m_nonZeros = 0;
  bool m_ok = false;
  std::vector<int> m_perm;       // row k of P A P^T is row m_perm[k] of A
  std::vector<double> m_invDiagonal;
  // Sequential: L by columns; the diagonal entry opens every column.
  std::vector<int> m_colStart;   // n + 1
  std::vector<int> m_row;
  std::vector<double> m_value;
  std::vector<int> m_reached;    // the interface's columns and their ancestors, ascending
  // SubtreeParallel: L by rows without the diagonal; the rows of each group of subtrees and of the separators
  // above them (the "top"), ascending.
  std::vector<int> m_rowStart, m_column;
  std::vector<double> m_rowValue;
  std::vector<std::vector<int>> m_groupRows;
  std::vector<int> m_topRows;
};

}  // namespace drape::pd
