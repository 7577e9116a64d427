#include "drape/garment/garment_transfer.h"

#include <limits>
#include <stdexcept>
#include <vector>

#include "drape/collision/distance.h"

namespace drape {
namespace {

Eigen::Vector3d inPlane(const Eigen::MatrixX2d& rest, int v) { return {rest(v, 0), rest(v, 1), 0.0}; }

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
    // The nearest point of the panel's triangles, in the pattern plane (z = 0).
    const Eigen::Vector3d p = inPlane(to.rest, v);
    collision::PointTriangleResult best;
    best.distanceSquared = std::numeric_limits<double>::infinity();
    int bestTriangle = -1;
    for (int f : candidates) {
      const collision::PointTriangleResult r = collision::closestPointTriangle(
          p, inPlane(from.rest, from.triangles(f, 0)), inPlane(from.rest, from.triangles(f, 1)),
          inPlane(from.rest, from.triangles(f, 2)));
      if (r.distanceSquared < best.distanceSquared) {
        best = r;
        bestTriangle = f;
        if (best.distanceSquared < 1e-24) break;  // inside it (to round-off): no nearer point
      }
    }
    for (int k = 0; k < 3; ++k)
      if (best.barycentric[k] != 0.0) entries.emplace_back(v, from.triangles(bestTriangle, k), best.barycentric[k]);
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> transfer(to.vertexCount(), from.vertexCount());
  transfer.setFromTriplets(entries.begin(), entries.end());
  return transfer;
}

}  // namespace drape
