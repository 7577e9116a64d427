#pragma once
// Percentiles of per-vertex quantities (kinetic energies, speeds): the early-stop and hand-over tests.
#include <algorithm>
#include <cmath>
#include <vector>

namespace drape {

// The value below which a fraction p of the values lie: the k-th smallest, k = ceil(p n) (nearest rank); 0 for none.
inline double percentile(std::vector<double> values, double p) {
  const int n = static_cast<int>(values.size());
  if (n == 0) return 0.0;
  const int k = std::clamp(static_cast<int>(std::ceil(p * n)) - 1, 0, n - 1);
  std::nth_element(values.begin(), values.begin() + k, values.end());
  return values[k];
}

}  // namespace drape
