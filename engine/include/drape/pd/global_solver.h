#pragma once
// Global step of Projective Dynamics (pd-dd eq. 3): K x = b for a constant SPD K, three right-hand sides (x, y,
// z coordinates). Two implementations: the monolithic CHOLMOD baseline here, the domain-decomposed solver in
// dd_solver.h. CHOLMOD stays behind a pImpl so users of these headers do not need its include path.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

namespace drape::pd {

class GlobalSolver {
 public:
  virtual ~GlobalSolver() = default;
  // b: n x 3; x: resized to n x 3. Thread-safe to call from one thread at a time; parallel inside.
  virtual void solve(const Eigen::MatrixX3d& b, Eigen::MatrixX3d& x) const = 0;
  virtual int size() const = 0;
  // False when a factorisation failed (K not positive definite).
  virtual bool ok() const = 0;
};

// Baseline: one CHOLMOD supernodal Cholesky of the whole K; sequential forward/back substitution.
class MonolithicSolver final : public GlobalSolver {
 public:
  explicit MonolithicSolver(const Eigen::SparseMatrix<double>& k);
  ~MonolithicSolver() override;
  void solve(const Eigen::MatrixX3d& b, Eigen::MatrixX3d& x) const override;
  int size() const override { return m_size; }
  bool ok() const override { return m_ok; }

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
  int m_size = 0;
  bool m_ok = false;
};

}  // namespace drape::pd
