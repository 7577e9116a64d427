#include "drape/pd/anderson.h"

#include <Eigen/Dense>
#include <algorithm>

namespace drape::pd {

Eigen::MatrixX3d AndersonMixer::next(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& g) {
  const Eigen::Index n = x.size();
  const Eigen::Map<const Eigen::VectorXd> gv(g.data(), n), xv(x.data(), n);
  const Eigen::VectorXd f = gv - xv;
  const double norm = f.norm();
  if (m_dF.rows() != n) {
    m_dF.resize(n, m_window);
    m_dG.resize(n, m_window);
    reset();
  }
  if (m_have && norm > m_lastNorm) {  // safeguard: the residual grew; restart from the plain step
    reset();
    ++m_restarts;
  }
  if (m_have) {
    m_dF.col(m_head) = f - m_fPrev;
    m_dG.col(m_head) = gv - m_gPrev;
    m_head = (m_head + 1) % m_window;
    m_count = std::min(m_count + 1, m_window);
  }
  m_fPrev = f;
  m_gPrev = gv;
  m_have = true;
  m_lastNorm = norm;
  if (m_count == 0) return g;
  const auto dF = m_dF.leftCols(m_count);
  const auto dG = m_dG.leftCols(m_count);
  Eigen::MatrixXd normal = dF.transpose() * dF;
  normal.diagonal().array() += 1e-10 * normal.diagonal().maxCoeff() + 1e-300;
  const Eigen::VectorXd gamma = normal.ldlt().solve(dF.transpose() * f);
  Eigen::MatrixX3d out(x.rows(), 3);
  Eigen::Map<Eigen::VectorXd>(out.data(), n) = gv - dG * gamma;
  if (!out.allFinite()) {
    reset();
    return g;
  }
  return out;
}

}  // namespace drape::pd
