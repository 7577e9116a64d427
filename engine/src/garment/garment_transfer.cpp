#include "drape/garment/garment_transfer.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <vector>

namespace drape {
namespace {

struct Nearest {
  double distance2 = std::numeric_limits<double>::infinity();
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
};

// Nearest point of the 2D triangle (a, b, c) to p, as barycentric weights, and its squared distance.
Nearest nearestOnTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                          const Eigen::Vector2d& c) {
  Nearest out;
  const Eigen::Vector2d e1 = b - a, e2 = c - a, d = p - a;
  const double det = e1.x() * e2.y() - e1.y() * e2.x();
  if (det != 0.0) {
    const double u = (d.x() * e2.y() - d.y() * e2.x()) / det;
    const double w = (e1.x() * d.y() - e1.y() * d.x()) / det;
    if (u >= 0.0 && w >= 0.0 && u + w <= 1.0) {
      out.distance2 = 0.0;
      out.weights = Eigen::Vector3d(std::max(0.0, 1.0 - u - w), u, w);  // round-off can leave -1e-16
      out.weights /= out.weights.sum();
      return out;
    }
  }
  // Outside (or degenerate): the nearest point of the three sides.
  const Eigen::Vector2d corners[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d& s = corners[k];
    const Eigen::Vector2d side = corners[(k + 1) % 3] - s;
    const double len2 = side.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - s).dot(side) / len2, 0.0, 1.0) : 0.0;
    const double dist2 = (s + t * side - p).squaredNorm();
    if (dist2 < out.distance2) {
      out.distance2 = dist2;
      out.weights.setZero();
      out.weights[k] = 1.0 - t;
      out.weights[(k + 1) % 3] = t;
    }
  }
  return out;
}

}  // namespace

Eigen::SparseMatrix<double, Eigen::RowMajor> garmentTransfer(const Garment& from, const Garment& to) {
  if (from.panelNames != to.panelNames)
    throw std::invalid_argument("garment transfer: the two garments do not mesh the same panels");
  std::vector<std::vector<int>> panelTriangles(from.panelNames.size());
  for (int f = 0; f < from.triangleCount(); ++f) panelTriangles[from.trianglePanel[f]].push_back(f);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(3 * static_cast<size_t>(to.vertexCount()));
  for (int v = 0; v < to.vertexCount(); ++v) {
    const int panel = to.vertexPanel[v];
    const std::vector<int>& candidates = panelTriangles[panel];
    if (candidates.empty())
      throw std::invalid_argument("garment transfer: panel '" + to.panelNames[panel] + "' has no triangle");
    const Eigen::Vector2d p = to.rest.row(v).transpose();
    Nearest best;
    int bestTriangle = -1;
    for (int f : candidates) {
      const Nearest n = nearestOnTriangle(p, from.rest.row(from.triangles(f, 0)).transpose(),
                                          from.rest.row(from.triangles(f, 1)).transpose(),
                                          from.rest.row(from.triangles(f, 2)).transpose());
      if (n.distance2 < best.distance2) {
        best = n;
        bestTriangle = f;
      }
      if (best.distance2 == 0.0) break;
    }
    for (int k = 0; k < 3; ++k)
      if (best.weights[k] != 0.0) entries.emplace_back(v, from.triangles(bestTriangle, k), best.weights[k]);
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> transfer(to.vertexCount(), from.vertexCount());
  transfer.setFromTriplets(entries.begin(), entries.end());
  return transfer;
}

}  // namespace drape
