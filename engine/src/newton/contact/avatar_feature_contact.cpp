#include "drape/newton/contact/avatar_feature_contact.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace drape::newton {

AvatarFeatureContactEnergy::AvatarFeatureContactEnergy(std::vector<collision::FeatureVertex> features,
                                                       const Eigen::MatrixX3i& garmentTriangles,
                                                       ContactParameters params, double reach)
    : m_features(std::move(features)),
      m_triangles(garmentTriangles),
      m_params(params),
      m_penalty(params),
      m_reach(reach) {}

void AvatarFeatureContactEnergy::beginStep(const StepContext& ctx) {
  const Eigen::VectorXd& x = *ctx.previousPositions;
  // Triangles crossed between the reach behind the feature and twice the thickness in front (the step's motion
  // is far below the thickness).
  m_pairs = collision::findFeaturePairs(m_features, m_triangles, x, 2.0 * m_params.thickness, m_reach, m_bvh);
}

double AvatarFeatureContactEnergy::gap(const collision::FeaturePair& pair, const Eigen::VectorXd& x) const {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) point += pair.weights[k] * x.segment<3>(3 * pair.vertices[k]);
  const collision::FeatureVertex& fv = m_features[pair.feature];
  return fv.normal.dot(point - fv.position);
}

std::vector<collision::ContactStencil> AvatarFeatureContactEnergy::contacts(const Eigen::VectorXd& x) const {
  std::vector<collision::ContactStencil> out;
  for (const collision::FeaturePair& pair : m_pairs) {
    const double s = gap(pair, x);
    if (s >= m_params.thickness) continue;
    collision::ContactStencil c;
    c.count = 3;
    for (int k = 0; k < 3; ++k) {
      c.vertices[k] = pair.vertices[k];
      c.weights[k] = pair.weights[k];
    }
    c.distance = s;
    c.normal = m_features[pair.feature].normal;
    out.push_back(c);
  }
  return out;
}

double AvatarFeatureContactEnergy::value(const Eigen::VectorXd& x) const {
  double e = 0.0;
  for (const collision::FeaturePair& pair : m_pairs) {
    const double s = gap(pair, x);
    if (s < m_params.thickness) e += m_penalty.energy(s);
  }
  return e;
}

void AvatarFeatureContactEnergy::addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
  for (const collision::FeaturePair& pair : m_pairs) {
    const double s = gap(pair, x);
    if (s >= m_params.thickness) continue;
    const Eigen::Vector3d push = m_penalty.force(s) * m_features[pair.feature].normal;  // -dE/ds n
    for (int k = 0; k < 3; ++k) g.segment<3>(3 * pair.vertices[k]) -= pair.weights[k] * push;
  }
}

void AvatarFeatureContactEnergy::addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const {
  for (const collision::FeaturePair& pair : m_pairs) {
    const double s = gap(pair, x);
    if (s >= m_params.thickness) continue;
    const Eigen::Vector3d& n = m_features[pair.feature].normal;
    const Eigen::Matrix3d nn = m_penalty.stiffnessAt(s) * n * n.transpose();
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) {
        const double w = pair.weights[i] * pair.weights[j];
        const int vi = pair.vertices[i], vj = pair.vertices[j];
        if (vi == vj)
          h.addDynamicBlock(vi, vi, (i == j ? 1.0 : 2.0) * w * nn);
        else
          h.addDynamicBlock(vi, vj, w * nn);
      }
  }
}

}  // namespace drape::newton
