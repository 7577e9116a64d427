// Block matrices shared by the linear-solve tests: a grid's couplings under a shuffled numbering, and SPD values.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include "drape/newton/block_matrix.h"

namespace drape::newton {

// Couplings of an n x n grid triangulated as gridCloth() (edges and diagonals), vertices renamed by a seeded shuffle
// so that the input numbering has a large bandwidth.
inline std::vector<std::pair<int, int>> shuffledGridCouplings(int n, unsigned seed, std::vector<int>* name = nullptr) {
  std::vector<int> id(n * n);
  std::iota(id.begin(), id.end(), 0);
  std::shuffle(id.begin(), id.end(), std::mt19937(seed));
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j;
      if (j + 1 < n) pairs.emplace_back(id[a], id[a + 1]);
      if (i + 1 < n) pairs.emplace_back(id[a], id[a + n]);
      if (i + 1 < n && j + 1 < n) pairs.emplace_back(id[a], id[a + n + 1]);
    }
  if (name) *name = id;
  return pairs;
}

// An SPD block matrix on the shuffled grid pattern: random symmetric couplings, diagonally dominant diagonal.
inline void fillSpd(BlockMatrix& a, const std::vector<std::pair<int, int>>& pairs, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  a.setZero();
  std::vector<double> rowSum(a.numBlocks(), 0.0);
  for (const auto& [i, j] : pairs) {
    Eigen::Matrix3d b = Eigen::Matrix3d::NullaryExpr([&] { return u(rng); });
    a.addBlock(i, j, b);
    rowSum[i] += b.cwiseAbs().sum();
    rowSum[j] += b.cwiseAbs().sum();
  }
  for (int i = 0; i < a.numBlocks(); ++i) {
    Eigen::Matrix3d d = Eigen::Matrix3d::NullaryExpr([&] { return u(rng); });
    a.addBlock(i, i, d + d.transpose() + (rowSum[i] + 6.0) * Eigen::Matrix3d::Identity());
  }
}

}  // namespace drape::newton
