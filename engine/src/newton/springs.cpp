#include "drape/newton/springs.h"

#include <algorithm>

namespace drape::newton {

StitchSprings::StitchSprings(std::vector<std::pair<int, int>> pairs, double stiffness,
                             const std::vector<model::EdgeStitch>& edges)
    : m_stiffness(stiffness) {
  m_stencils.reserve(pairs.size() + edges.size());
  for (auto [i, j] : pairs)
    if (i != j) m_stencils.push_back(Stencil{{i, j, 0}, {1.0, -1.0, 0.0}, 2});  // (v, v): no energy, skipped
  for (const model::EdgeStitch& e : edges) m_stencils.push_back(Stencil{{e.vertex, e.a, e.b}, {1.0, -(1.0 - e.t), -e.t}, 3});
}

Eigen::Vector3d StitchSprings::constraint(const Stencil& s, const Eigen::VectorXd& x) const {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k = 0; k < s.size; ++k) c += s.w[k] * x.segment<3>(3 * s.vertices[k]);
  return c;
}

double StitchSprings::value(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (const Stencil& s : m_stencils) sum += constraint(s, x).squaredNorm();
  return 0.5 * m_stiffness * sum;
}

// dE/dx_k = k w_k c.
void StitchSprings::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  for (const Stencil& s : m_stencils) {
    const Eigen::Vector3d f = m_stiffness * constraint(s, x);
    for (int k = 0; k < s.size; ++k) g.segment<3>(3 * s.vertices[k]) += s.w[k] * f;
  }
}

// d2E/dx_k dx_l = k w_k w_l I (constant).
void StitchSprings::addHessian(const Eigen::VectorXd&, BlockMatrix& h) const {
  for (const Stencil& s : m_stencils)
    for (int k = 0; k < s.size; ++k)
      for (int l = k; l < s.size; ++l)
        h.addBlock(s.vertices[k], s.vertices[l], (m_stiffness * s.w[k] * s.w[l]) * Eigen::Matrix3d::Identity());
}

void StitchSprings::addCouplings(std::vector<std::pair<int, int>>& pairs) const {
  for (const Stencil& s : m_stencils)
    for (int k = 0; k < s.size; ++k)
      for (int l = k + 1; l < s.size; ++l) pairs.emplace_back(s.vertices[k], s.vertices[l]);
}

double StitchSprings::maxGap(const Eigen::VectorXd& x) const {
  double gap = 0.0;
  for (const Stencil& s : m_stencils) gap = std::max(gap, constraint(s, x).norm());
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
