#include "drape/geometry/spatial_order.h"

#include <algorithm>
#include <numeric>

namespace drape {
namespace {

constexpr int kBits = 16;
constexpr unsigned kSide = 1u << kBits;

// Distance of cell (x, y) along the Hilbert curve filling a kSide x kSide grid (the classic rotate-and-flip
// walk from the largest quadrant down).
unsigned long long hilbertIndex(unsigned x, unsigned y) {
  unsigned long long d = 0;
  for (unsigned s = kSide / 2; s > 0; s /= 2) {
    const unsigned rx = (x & s) ? 1u : 0u;
    const unsigned ry = (y & s) ? 1u : 0u;
    d += static_cast<unsigned long long>(s) * s * ((3u * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) {
        x = kSide - 1 - x;
        y = kSide - 1 - y;
      }
      std::swap(x, y);
    }
  }
  return d;
}

}  // namespace

std::vector<unsigned long long> hilbertKeys(const Eigen::MatrixX2d& points) {
  std::vector<unsigned long long> keys(static_cast<size_t>(points.rows()), 0);
  if (points.rows() == 0) return keys;
  const Eigen::RowVector2d lo = points.colwise().minCoeff();
  const double extent = (points.colwise().maxCoeff() - lo).maxCoeff();
  const double scale = extent > 0.0 ? (kSide - 1) / extent : 0.0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::RowVector2d c = (points.row(i) - lo) * scale;
    const auto cell = [](double v) { return static_cast<unsigned>(std::clamp(v, 0.0, double(kSide - 1))); };
    keys[static_cast<size_t>(i)] = hilbertIndex(cell(c.x()), cell(c.y()));
  }
  return keys;
}

std::vector<int> hilbertOrder(const Eigen::MatrixX2d& points) {
  const std::vector<unsigned long long> keys = hilbertKeys(points);
  std::vector<int> order(keys.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&keys](int a, int b) { return keys[a] < keys[b]; });
  return order;
}

}  // namespace drape
