#include "drape/collision/avatar_features.h"

#include <Eigen/Geometry>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "drape/collision/aabb.h"

namespace drape::collision {

std::vector<FeatureVertex> avatarFeatureVertices(const TriangleMesh& avatar, double maxRadius) {
  const int n = avatar.vertexCount();
  std::vector<Eigen::Vector3d> normal(n, Eigen::Vector3d::Zero());
  std::vector<std::vector<int>> neighbours(n);
  std::map<std::pair<int, int>, int> edgeUses;  // an edge used once lies on an open boundary
  for (int f = 0; f < avatar.triangleCount(); ++f) {
    const Eigen::Vector3i t = avatar.triangles.row(f);
    const Eigen::Vector3d a = avatar.vertices.row(t[0]), b = avatar.vertices.row(t[1]), c = avatar.vertices.row(t[2]);
    const Eigen::Vector3d areaNormal = (b - a).cross(c - a);  // twice the area, outward (counter-clockwise)
    for (int k = 0; k < 3; ++k) {
      normal[t[k]] += areaNormal;
      const int i = t[k], j = t[(k + 1) % 3];
      neighbours[i].push_back(j);
      neighbours[j].push_back(i);
      ++edgeUses[{std::min(i, j), std::max(i, j)}];
    }
  }
  std::vector<char> boundary(n, 0);
  for (const auto& [edge, uses] : edgeUses)
    if (uses == 1) boundary[edge.first] = boundary[edge.second] = 1;
  std::vector<FeatureVertex> out;
  for (int v = 0; v < n; ++v) {
    if (boundary[v] || neighbours[v].empty() || normal[v].squaredNorm() == 0.0) continue;
    const Eigen::Vector3d p = avatar.vertices.row(v);
    const Eigen::Vector3d nv = normal[v].normalized();
    bool peak = true;
    double radius = std::numeric_limits<double>::infinity();
    for (int q : neighbours[v]) {
      const Eigen::Vector3d d = p - Eigen::Vector3d(avatar.vertices.row(q));
      const double height = nv.dot(d);
      if (!(height > 0.0)) {
        peak = false;
        break;
      }
      radius = std::min(radius, d.squaredNorm() / (2.0 * height));
    }
    if (peak && radius < maxRadius) out.push_back({p, nv});
  }
  return out;
}

double featureRadiusFor(double meanEdge, double thickness) {
  return std::min(meanEdge * meanEdge / (4.0 * thickness), kMaxFeatureRadius);
}

double meanEdgeLength(const Eigen::MatrixX3i& triangles, const Eigen::Ref<const Eigen::MatrixXd>& positions) {
  if (triangles.rows() == 0) return 0.0;
  double length = 0.0;
  for (int t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      length += (positions.row(triangles(t, k)) - positions.row(triangles(t, (k + 1) % 3))).norm();
  return length / (3.0 * static_cast<double>(triangles.rows()));
}

std::vector<FeaturePair> findFeaturePairs(const std::vector<FeatureVertex>& features, const Eigen::MatrixX3i& triangles,
                                          const Eigen::VectorXd& x, double ahead, double behind, Bvh& bvh) {
  const int nt = static_cast<int>(triangles.rows());
  std::vector<Eigen::Vector3d> corners(3 * static_cast<size_t>(nt));
  std::vector<BoundingBox> boxes(nt);
  for (int f = 0; f < nt; ++f) {
    for (int k = 0; k < 3; ++k) corners[3 * f + k] = x.segment<3>(3 * triangles(f, k));
    boxes[f] = boxOf(corners[3 * f], corners[3 * f + 1], corners[3 * f + 2]);
  }
  if (bvh.primitiveCount() == nt)
    bvh.refit(boxes);
  else
    bvh.build(boxes);
  tbb::enumerable_thread_specific<std::vector<FeaturePair>> local;
  tbb::parallel_for(
      tbb::blocked_range<int>(0, static_cast<int>(features.size())), [&](const tbb::blocked_range<int>& range) {
        auto& out = local.local();
        for (int i = range.begin(); i < range.end(); ++i) {
          const FeatureVertex& fv = features[i];
          const BoundingBox reach = boxOf(fv.position - behind * fv.normal, fv.position + ahead * fv.normal);
          FeaturePair best;
          double bestAlong = std::numeric_limits<double>::infinity();
          bvh.forEachOverlap(reach, [&](int f) {
            const Eigen::Vector3d& a = corners[3 * f];
            // Line p + s n against the triangle's plane, in barycentric coordinates (Moller-Trumbore).
            const Eigen::Vector3d e1 = corners[3 * f + 1] - a, e2 = corners[3 * f + 2] - a, h = fv.normal.cross(e2);
            const double det = e1.dot(h);
            if (std::abs(det) < 1e-18) return;
            const Eigen::Vector3d sv = fv.position - a;
            const double u = sv.dot(h) / det;
            const Eigen::Vector3d q = sv.cross(e1);
            const double w = fv.normal.dot(q) / det;
            if (u < 0.0 || w < 0.0 || u + w > 1.0) return;
            const double along = e2.dot(q) / det;
            if (along < -behind || along > ahead || std::abs(along) >= std::abs(bestAlong)) return;
            bestAlong = along;
            best.feature = i;
            best.vertices = {triangles(f, 0), triangles(f, 1), triangles(f, 2)};
            best.weights = Eigen::Vector3d(1.0 - u - w, u, w);
          });
          if (std::isfinite(bestAlong)) out.push_back(best);
        }
      });
  std::vector<FeaturePair> pairs;
  for (auto& part : local) pairs.insert(pairs.end(), part.begin(), part.end());
  std::sort(pairs.begin(), pairs.end(),
            [](const FeaturePair& a, const FeaturePair& b) { return a.feature < b.feature; });
  return pairs;
}

}  // namespace drape::collision
