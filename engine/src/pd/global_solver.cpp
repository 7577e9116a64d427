#include "drape/pd/global_solver.h"

#include <Eigen/CholmodSupport>

namespace drape::pd {

struct MonolithicSolver::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
};

MonolithicSolver::MonolithicSolver(const Eigen::SparseMatrix<double>& k)
    : m_impl(std::make_unique<Impl>()), m_size(static_cast<int>(k.rows())) {
  if (m_size == 0) {
    m_ok = true;
    return;
  }
  m_impl->llt.compute(k);
  m_ok = m_impl->llt.info() == Eigen::Success;
}

MonolithicSolver::~MonolithicSolver() = default;

void MonolithicSolver::solve(const Eigen::MatrixX3d& b, Eigen::MatrixX3d& x) const {
  if (m_size == 0 || !m_ok) {
    x.setZero(b.rows(), 3);
    return;
  }
  x = m_impl->llt.solve(b);
}

}  // namespace drape::pd
