#include "drape/trade/pareto.h"

#include <cstddef>

namespace drape::trade {

std::vector<bool> paretoFront(const std::vector<std::pair<double, double>>& points) {
  std::vector<bool> front(points.size(), true);
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = 0; j < points.size() && front[i]; ++j) {
      const auto& [a, b] = points[j];
      const auto& [ai, bi] = points[i];
      if (a <= ai && b <= bi && (a < ai || b < bi)) front[i] = false;
    }
  return front;
}

}  // namespace drape::trade
