// Lagged, mollified Coulomb friction; see friction.h for the potential and its derivatives.
#include "drape/newton/contact/friction.h"

#include <cmath>

namespace drape::newton {

double frictionF0(double y, double eps) {
  if (y >= eps) return y;
  return -y * y * y / (3.0 * eps * eps) + y * y / eps + eps / 3.0;
}

double frictionF1(double y, double eps) {
  if (y >= eps) return 1.0;
  return 2.0 * y / eps - y * y / (eps * eps);
}

FrictionEnergy::FrictionEnergy(const AvatarContactEnergy* avatar, const SelfContactEnergy* self,
                               FrictionParameters params, const AvatarFeatureContactEnergy* features)
    : m_avatar(avatar), m_self(self), m_features(features), m_params(params) {}

void FrictionEnergy::setLagged(std::vector<LaggedContact> contacts, const Eigen::VectorXd& start, double h) {
  m_contacts = std::move(contacts);
  m_start = start;
  m_eps = std::max(m_params.epsV * h, 1e-12);
}

void FrictionEnergy::beginStep(const StepContext& ctx) {
  const Eigen::VectorXd& xn = *ctx.previousPositions;
  std::vector<LaggedContact> contacts;
  auto add = [&](const std::vector<collision::ContactStencil>& stencils, const ContactParameters& p) {
    for (const collision::ContactStencil& s : stencils) {
      LaggedContact c;
      c.stencil = s;
      c.normalForce = p.stiffness * (p.thickness - s.distance);
      c.tangent = Eigen::Matrix3d::Identity() - s.normal * s.normal.transpose();
      if (c.normalForce > 0.0) contacts.push_back(c);
    }
  };
  if (m_avatar) add(m_avatar->contacts(xn), m_avatar->parameters());
  if (m_self) add(m_self->contacts(xn), m_self->parameters());
  if (m_features) add(m_features->contacts(xn), m_features->parameters());
  setLagged(std::move(contacts), xn, ctx.h);
}

Eigen::Vector3d FrictionEnergy::slip(const LaggedContact& c, const Eigen::VectorXd& x) const {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (int i = 0; i < c.stencil.count; ++i) {
    const int v = c.stencil.vertices[i];
    r += c.stencil.weights[i] * (x.segment<3>(3 * v) - m_start.segment<3>(3 * v));
  }
  return c.tangent * r;
}

double FrictionEnergy::value(const Eigen::VectorXd& x) const {
  double e = 0.0;
  for (const LaggedContact& c : m_contacts) e += m_params.mu * c.normalForce * frictionF0(slip(c, x).norm(), m_eps);
  return e;
}

void FrictionEnergy::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  for (const LaggedContact& c : m_contacts) {
    const Eigen::Vector3d u = slip(c, x);
    const double y = u.norm();
    // f1(y) / y, finite as y -> 0 (2 / eps).
    const double ratio = y >= m_eps ? 1.0 / y : (2.0 - y / m_eps) / m_eps;
    const Eigen::Vector3d force = m_params.mu * c.normalForce * ratio * u;  // u is tangential already
    for (int i = 0; i < c.stencil.count; ++i) g.segment<3>(3 * c.stencil.vertices[i]) += c.stencil.weights[i] * force;
  }
}

void FrictionEnergy::addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const {
  addBlocks(x, h, false);
}

void FrictionEnergy::addPredictionGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g,
                                                     BlockMatrix& h) const {
  addGradient(x, g);
  addBlocks(x, h, m_params.majorizeAtPrediction);
}

void FrictionEnergy::addBlocks(const Eigen::VectorXd& x, BlockMatrix& h, bool majorizer) const {
  for (const LaggedContact& c : m_contacts) {
    const Eigen::Vector3d u = slip(c, x);
    const double y = u.norm();
    Eigen::Matrix3d inner;
    if (majorizer) {
      inner = (y >= m_eps ? 1.0 / y : (2.0 - y / m_eps) / m_eps) * Eigen::Matrix3d::Identity();  // f1(y) / y
    } else if (y >= m_eps) {
      inner = (Eigen::Matrix3d::Identity() - u * u.transpose() / (y * y)) / y;  // f1 = 1, f1' = 0
    } else {
      // f1/y = (2 - y/eps)/eps and (f1' y - f1)/y^3 = -1 / (eps^2 y); the product with u u^T is bounded.
      inner = (2.0 - y / m_eps) / m_eps * Eigen::Matrix3d::Identity();
      if (y > 0.0) inner -= u * u.transpose() / (m_eps * m_eps * y);
    }
    const Eigen::Matrix3d block = m_params.mu * c.normalForce * c.tangent * inner * c.tangent;
    for (int i = 0; i < c.stencil.count; ++i) {
      for (int j = i; j < c.stencil.count; ++j) {
        const double w = c.stencil.weights[i] * c.stencil.weights[j];
        const int vi = c.stencil.vertices[i];
        const int vj = c.stencil.vertices[j];
        if (vi == vj) {
          h.addDynamicBlock(vi, vi, (i == j ? 1.0 : 2.0) * w * block);
        } else {
          h.addDynamicBlock(vi, vj, w * block);
        }
      }
    }
  }
}

}  // namespace drape::newton
