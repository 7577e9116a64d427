#include "drape/newton/body_forces.h"

#include <cmath>

namespace drape::newton {

Eigen::VectorXd lumpedVertexMasses(const model::ClothModel& model) {
  Eigen::VectorXd m = Eigen::VectorXd::Zero(model.numVertices());
  for (int t = 0; t < model.triangles.rows(); ++t) {
    Eigen::Vector2d p0 = model.restCoords.row(model.triangles(t, 0)).transpose();
    Eigen::Vector2d e1 = model.restCoords.row(model.triangles(t, 1)).transpose() - p0;
    Eigen::Vector2d e2 = model.restCoords.row(model.triangles(t, 2)).transpose() - p0;
    double area = 0.5 * std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    for (int k = 0; k < 3; ++k) m(model.triangles(t, k)) += model.fabric(t).density * area / 3.0;
  }
  return m;
}

Gravity::Gravity(Eigen::VectorXd masses, const Eigen::Vector3d& g) : m_force(3 * masses.size()) {
  for (int i = 0; i < masses.size(); ++i) m_force.segment<3>(3 * i) = masses(i) * g;
}

double Gravity::value(const Eigen::VectorXd& x) const { return -m_force.dot(x); }

void Gravity::addGradient(const Eigen::VectorXd&, Eigen::VectorXd& g) const { g -= m_force; }

AirDrag::AirDrag(Eigen::VectorXd masses, double alpha) : m_masses(std::move(masses)), m_alpha(alpha) {}

void AirDrag::beginStep(const StepContext& ctx) {
  m_h = ctx.h;
  m_previous = ctx.previousPositions;
}

double AirDrag::value(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (int i = 0; i < m_masses.size(); ++i)
    sum += m_masses(i) * (x.segment<3>(3 * i) - m_previous->segment<3>(3 * i)).squaredNorm();
  return m_alpha * sum / (2.0 * m_h);
}

void AirDrag::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  for (int i = 0; i < m_masses.size(); ++i)
    g.segment<3>(3 * i) += (m_alpha * m_masses(i) / m_h) * (x.segment<3>(3 * i) - m_previous->segment<3>(3 * i));
}

void AirDrag::addHessian(const Eigen::VectorXd&, BlockMatrix& h) const {
  for (int i = 0; i < m_masses.size(); ++i)
    h.diagonalBlock(i).diagonal().array() += m_alpha * m_masses(i) / m_h;  // = addBlock(i, i, c I), no search
}

}  // namespace drape::newton
