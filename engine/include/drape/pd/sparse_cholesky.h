#pragma once
// A sparse Cholesky factor P A P^T = L L^T kept as plain compressed columns, solved for three right-hand sides at
// once (the x, y, z coordinates of the Projective Dynamics global step, pd-dd eq. 3). CHOLMOD computes the
// ordering and the simplicial factor once; the solves are our own loops so that each non-zero of L is read once
// in the forward and once in the backward pass for all three columns, with no allocation (the per-iteration
// bandwidth floor of the global step; see docs/BENCHMARKS.md, "Time per L-G iteration").
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace drape::pd {

class SparseCholesky {
 public:
  SparseCholesky() = default;
  // a: symmetric positive definite n x n (both triangles stored or only the lower one; the lower one is read).
  // Returns false (and ok() stays false) when a is not numerically positive definite.
  bool factor(const Eigen::SparseMatrix<double>& a);
  bool ok() const { return m_ok; }
  int size() const { return m_n; }
  long nonZeros() const { return static_cast<long>(m_value.size()); }  // non-zeros of L

  // In place: x (n x 3, row-major: x[3 i + c]) <- A^-1 x. work: 3 n doubles of scratch, overwritten.
  void solveInPlace(double* x, double* work) const;
  // Columns of b (n x k, any k) solved three at a time; returns A^-1 b. For setup, not per iteration.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const;

 private:
  int m_n = 0;
  bool m_ok = false;
  std::vector<int> m_perm;       // row k of P A P^T is row m_perm[k] of A
  std::vector<int> m_colStart;   // n + 1; the diagonal entry opens every column
  std::vector<int> m_row;
  std::vector<double> m_value;
  std::vector<double> m_invDiagonal;
};

}  // namespace drape::pd
