#pragma once
// The avatar's sharp features (points where the body curves more tightly than a garment triangle spans, such as a
// bust point or a shoulder tip) and the garment triangles facing them along their normals. Geometry only: the
// Newton drape's feature contact (newton/contact/avatar_feature_contact.h) pushes those triangles out.
//
// Feature vertices are the avatar vertices that stand above all their neighbours (along the vertex normal n) with
// a radius of curvature below maxRadius in some direction: R = |q - p|^2 / (2 n.(p - q)) over the neighbours q.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "drape/collision/bvh.h"
#include "drape/geometry/triangle_mesh.h"

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
std::vector<FeaturePair> findFeaturePairs(const std::vector<FeatureVertex>& features, const Eigen::MatrixX3i& triangles,
                                          const Eigen::VectorXd& x, double ahead, double behind, Bvh& bvh);

}  // namespace drape::collision
