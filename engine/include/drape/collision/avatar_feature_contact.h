#pragma once
// The avatar's sharp features against the garment's triangles, for the Newton drape. Avatar contact
// (avatar_contact.h) keeps every garment *vertex* out of the body; between its vertices a garment triangle is flat,
// and where the body curves more tightly than the triangle spans (a bust point, a shoulder tip under a 2 cm mesh)
// the body pokes through the triangle although every vertex is outside it. This term pushes those triangles out.
//
// Feature vertices are the avatar vertices that stand above all their neighbours (along the vertex normal n) with
// a radius of curvature below maxRadius in some direction: R = |q - p|^2 / (2 n.(p - q)) over the neighbours q.
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

#include "drape/collision/avatar_contact.h"
#include "drape/collision/bvh.h"
#include "drape/geometry/triangle_mesh.h"
#include "drape/newton/energy.h"

namespace drape::collision {

struct FeatureVertex {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, outward
};

// Avatar vertices standing above every neighbour along their area-weighted normal, with the smallest radius of
// curvature towards a neighbour below maxRadius (metres). Vertices on an open boundary are not features.
std::vector<FeatureVertex> avatarFeatureVertices(const TriangleMesh& avatar, double maxRadius);

// The radius bound for a garment of mean edge length meanEdge and contact thickness t (metres):
// over a cap of radius R a triangle sags about meanEdge^2 / (8 R) below its vertices, which the vertex contact keeps
// 0 to t off the body, so features whose sag reaches t / 2 are taken, up to kMaxFeatureRadius (on a coarse mesh
// the bound would take in the whole body, and blunt features holding every triangle slow the drape down).
constexpr double kMaxFeatureRadius = 0.03;
double featureRadiusFor(double meanEdge, double thickness);
// Mean edge length of a triangle mesh (positions |V| x 3, or rest coordinates |V| x 2; metres); 0 without
// triangles. Every triangle must name existing rows.
double meanEdgeLength(const Eigen::MatrixX3i& triangles, const Eigen::Ref<const Eigen::MatrixXd>& positions);

// A feature facing a garment triangle: the triangle's point at barycentric weights w lies on the feature's normal.
struct FeaturePair {
  int feature = 0;
  std::array<int, 3> vertices{};
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // barycentric, sum 1
};

// For every feature, the garment triangle whose crossing with the feature's normal line lies nearest to it, between
// `behind` metres behind it and `ahead` in front; x: garment positions, flat (3|V|). bvh: over the triangles, kept
// by the caller between calls (built when its size differs, refitted otherwise).
std::vector<FeaturePair> findFeaturePairs(const std::vector<FeatureVertex>& features,
                                          const Eigen::MatrixX3i& triangles, const Eigen::VectorXd& x, double ahead,
                                          double behind, Bvh& bvh);

class AvatarFeatureContactEnergy : public newton::Energy {
 public:
  // garmentTriangles: |F| x 3 into the garment's vertices. params: the avatar contact's (stiffness,
  // thickness, insideStiffnessFactor). reach: metres behind a feature within which a triangle is still pushed out
  // (about half a garment edge: a triangle whose vertices are outside the body is not deeper than its sag).
  AvatarFeatureContactEnergy(std::vector<FeatureVertex> features, const Eigen::MatrixX3i& garmentTriangles,
                             ContactParameters params, double reach);

  std::string_view name() const override { return "avatar_feature_contact"; }
  void beginStep(const newton::StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, newton::BlockMatrix& h) const override;

  // Pairs within the thickness at x as 3-vertex stencils (the triangle's vertices and weights; distance s, normal
  // the feature's). Used by friction for its normal forces and slips.
  std::vector<ContactStencil> contacts(const Eigen::VectorXd& x) const;
  const ContactParameters& parameters() const { return m_params; }
  int featureCount() const { return static_cast<int>(m_features.size()); }
  // Feature-triangle pairs held for the current step.
  int pairCount() const { return static_cast<int>(m_pairs.size()); }

 private:
  double gap(const FeaturePair& pair, const Eigen::VectorXd& x) const;  // s(x)

  std::vector<FeatureVertex> m_features;
  Eigen::MatrixX3i m_triangles;
  ContactParameters m_params;
  AvatarPenalty m_penalty;
  double m_reach = 0.0;
  Bvh m_bvh;  // over the garment's triangles at x_n, built once and refitted every step
  std::vector<FeaturePair> m_pairs;
};

}  // namespace drape::collision
