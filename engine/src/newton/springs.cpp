#include "drape/newton/springs.h"

#include <algorithm>

namespace drape::newton {

StitchSprings::StitchSprings(std::vector<std::pair<int, int>> pairs, double stiffness)
    : m_pairs(std::move(pairs)), m_stiffness(stiffness) {}

double StitchSprings::value(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (auto [i, j] : m_pairs) sum += (x.segment<3>(3 * i) - x.segment<3>(3 * j)).squaredNorm();
  return 0.5 * m_stiffness * sum;
}

void StitchSprings::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  for (auto [i, j] : m_pairs) {
    Eigen::Vector3d f = m_stiffness * (x.segment<3>(3 * i) - x.segment<3>(3 * j));
    g.segment<3>(3 * i) += f;
    g.segment<3>(3 * j) -= f;
  }
}

void StitchSprings::addHessian(const Eigen::VectorXd&, BlockMatrix& h) const {
  Eigen::Matrix3d k = m_stiffness * Eigen::Matrix3d::Identity();
  for (auto [i, j] : m_pairs) {
    h.addBlock(i, i, k);
    h.addBlock(j, j, k);
    h.addBlock(i, j, -k);
  }
}

void StitchSprings::addCouplings(std::vector<std::pair<int, int>>& pairs) const {
  pairs.insert(pairs.end(), m_pairs.begin(), m_pairs.end());
}

double StitchSprings::maxGap(const Eigen::VectorXd& x) const {
  double gap = 0.0;
  for (auto [i, j] : m_pairs) gap = std::max(gap, (x.segment<3>(3 * i) - x.segment<3>(3 * j)).norm());
  return gap;
}

PinSprings::PinSprings(std::vector<int> vertices, std::vector<Eigen::Vector3d> targets, double stiffness,
                       Trajectory trajectory, double timeOffset, std::string name)
    : m_vertices(std::move(vertices)),
      m_targets(std::move(targets)),
      m_stiffness(stiffness),
      m_trajectory(std::move(trajectory)),
      m_timeOffset(timeOffset),
      m_name(std::move(name)) {}

void PinSprings::beginStep(const StepContext& ctx) {
  if (!m_trajectory) return;
  const double t = m_timeOffset + ctx.time + ctx.h;  // end of the step: backward Euler pulls towards it
  for (size_t k = 0; k < m_vertices.size(); ++k) m_targets[k] = m_trajectory(static_cast<int>(k), t);
}

void PinSprings::setPins(std::vector<int> vertices, std::vector<Eigen::Vector3d> targets) {
  m_vertices = std::move(vertices);
  m_targets = std::move(targets);
  m_trajectory = {};
}

double PinSprings::value(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (size_t k = 0; k < m_vertices.size(); ++k) sum += (x.segment<3>(3 * m_vertices[k]) - m_targets[k]).squaredNorm();
  return 0.5 * m_stiffness * sum;
}

void PinSprings::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  for (size_t k = 0; k < m_vertices.size(); ++k)
    g.segment<3>(3 * m_vertices[k]) += m_stiffness * (x.segment<3>(3 * m_vertices[k]) - m_targets[k]);
}

void PinSprings::addHessian(const Eigen::VectorXd&, BlockMatrix& h) const {
  for (int v : m_vertices) h.addBlock(v, v, m_stiffness * Eigen::Matrix3d::Identity());
}

}  // namespace drape::newton
