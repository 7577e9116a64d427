#pragma once
// The avatar's sharp features against the garment's triangles, for the Newton drape. Avatar contact
// (avatar_contact.h) keeps every garment *vertex* out of the body; between its vertices a garment triangle is flat,
// and where the body curves more tightly than the triangle spans (a bust point, a shoulder tip under a 2 cm mesh)
// the body pokes through the triangle although every vertex is outside it. This term pushes those triangles out.
//
// The features and the triangles facing them are geometry (collision/avatar_features.h).
// At the start of each step every feature vertex p looks along its normal for a garment triangle within reach;
// the point of that triangle at fixed barycentric weights w (those of the crossing at x_n) must stay at least the
// contact thickness t above p:
//   s(x) = n . (sum_i w_i x_i - p),   E = penalty(s), with the avatar contact's penalty in s
// (soft band 0 <= s < t with stiffness k, k x insideStiffnessFactor below 0). The pairs are fixed for the step, so
// E is one quadratic-by-parts function of x and its Hessian k w_i w_j n n^T is exact and positive semi-definite.
// Friction (friction.h) takes these pairs like the vertex contacts: the slip is that of the triangle's point.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "drape/collision/avatar_features.h"
#include "drape/collision/bvh.h"
#include "drape/geometry/triangle_mesh.h"
#include "drape/newton/contact/avatar_contact.h"
#include "drape/newton/energy.h"

namespace drape::newton {

class AvatarFeatureContactEnergy : public Energy {
 public:
  // garmentTriangles: |F| x 3 into the garment's vertices. params: the avatar contact's (stiffness,
  // thickness, insideStiffnessFactor). reach: metres behind a feature within which a triangle is still pushed out
  // (about half a garment edge: a triangle whose vertices are outside the body is not deeper than its sag).
  AvatarFeatureContactEnergy(std::vector<collision::FeatureVertex> features, const Eigen::MatrixX3i& garmentTriangles,
                             ContactParameters params, double reach);

  std::string_view name() const override { return "avatar_feature_contact"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;

  // Pairs within the thickness at x as 3-vertex stencils (the triangle's vertices and weights; distance s, normal
  // the feature's). Used by friction for its normal forces and slips.
  std::vector<collision::ContactStencil> contacts(const Eigen::VectorXd& x) const;
  const ContactParameters& parameters() const { return m_params; }
  int featureCount() const { return static_cast<int>(m_features.size()); }
  // Feature-triangle pairs held for the current step.
  int pairCount() const { return static_cast<int>(m_pairs.size()); }

 private:
  double gap(const collision::FeaturePair& pair, const Eigen::VectorXd& x) const;  // s(x)

  std::vector<collision::FeatureVertex> m_features;
  Eigen::MatrixX3i m_triangles;
  ContactParameters m_params;
  AvatarPenalty m_penalty;
  double m_reach = 0.0;
  collision::Bvh m_bvh;  // over the garment's triangles at x_n, built once and refitted every step
  std::vector<collision::FeaturePair> m_pairs;
};

}  // namespace drape::newton
