// Karras 2012 binary radix tree over Morton-sorted box centres; internal nodes are built independently of each
// other (TBB), then boxes are fitted bottom-up along a precomputed children-before-parents order.
#include "drape/collision/bvh.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cstdint>

namespace drape::collision {
namespace {

// Spreads the low 21 bits of v so that two zero bits follow each (x -> x00x00x...).
std::uint64_t spreadBits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

std::uint64_t mortonCode(const Eigen::Vector3d& unit) {
  const double scale = double((1 << 21) - 1);
  auto q = [&](double c) { return static_cast<std::uint64_t>(std::clamp(c, 0.0, 1.0) * scale); };
  return spreadBits(q(unit.x())) << 2 | spreadBits(q(unit.y())) << 1 | spreadBits(q(unit.z()));
}

}  // namespace

void Bvh::build(const std::vector<BoundingBox>& boxes) {
  m_count = static_cast<int>(boxes.size());
  m_nodes.assign(m_count == 0 ? 0 : 2 * m_count - 1, Node{});
  m_leafPrimitive.resize(m_count);
  m_refitOrder.clear();
  if (m_count == 0) return;

  BoundingBox centres;
  for (const BoundingBox& b : boxes) centres.extend(b.center());
  const Eigen::Vector3d extent = centres.size().cwiseMax(1e-30);
  std::vector<std::pair<std::uint64_t, int>> keys(m_count);
  tbb::parallel_for(0, m_count, [&](int i) {
    const Eigen::Vector3d unit = (boxes[i].center() - centres.min).cwiseQuotient(extent);
    keys[i] = {mortonCode(unit), i};
  });
  tbb::parallel_sort(keys.begin(), keys.end());
  for (int i = 0; i < m_count; ++i) m_leafPrimitive[i] = keys[i].second;

  // Length of the common prefix of sorted keys i and j; equal codes are told apart by their position
  // (Karras section 4). -1 outside the range.
  const int n = m_count;
  auto delta = [&](int i, int j) -> int {
    if (j < 0 || j >= n) return -1;
    const std::uint64_t a = keys[i].first;
    const std::uint64_t b = keys[j].first;
    if (a != b) return std::countl_zero(a ^ b);
    return 64 + std::countl_zero(static_cast<std::uint32_t>(i ^ j));
  };
  const int leafBase = n - 1;
  tbb::parallel_for(0, n - 1, [&](int i) {
    const int d = delta(i, i + 1) > delta(i, i - 1) ? 1 : -1;
    const int deltaMin = delta(i, i - d);
    int lengthMax = 2;
    while (delta(i, i + lengthMax * d) > deltaMin) lengthMax *= 2;
    int length = 0;
    for (int t = lengthMax / 2; t >= 1; t /= 2) {
      if (delta(i, i + (length + t) * d) > deltaMin) length += t;
    }
    const int j = i + length * d;
    const int deltaNode = delta(i, j);
    int split = 0;
    for (int t = (length + 1) / 2;; t = (t + 1) / 2) {
      if (delta(i, i + (split + t) * d) > deltaNode) split += t;
      if (t == 1) break;
    }
    const int gamma = i + split * d + std::min(d, 0);
    m_nodes[i].left = std::min(i, j) == gamma ? leafBase + gamma : gamma;
    m_nodes[i].right = std::max(i, j) == gamma + 1 ? leafBase + gamma + 1 : gamma + 1;
    m_nodes[i].last = std::max(i, j);
  });
  for (int k = 0; k < n; ++k) m_nodes[leafBase + k].last = k;

  // Breadth-first order from the root, reversed: children come before parents.
  if (n > 1) {
    m_refitOrder.reserve(n - 1);
    m_refitOrder.push_back(0);
    for (std::size_t k = 0; k < m_refitOrder.size(); ++k) {
      const Node& node = m_nodes[m_refitOrder[k]];
      if (node.left < leafBase) m_refitOrder.push_back(node.left);
      if (node.right < leafBase) m_refitOrder.push_back(node.right);
    }
    assert(static_cast<int>(m_refitOrder.size()) == n - 1);
    std::reverse(m_refitOrder.begin(), m_refitOrder.end());
  }
  refit(boxes);
}

void Bvh::refit(const std::vector<BoundingBox>& boxes) {
  assert(static_cast<int>(boxes.size()) == m_count);
  const int leafBase = m_count - 1;
  tbb::parallel_for(0, m_count, [&](int k) { m_nodes[leafBase + k].box = boxes[m_leafPrimitive[k]]; });
  for (int node : m_refitOrder) {
    Node& nd = m_nodes[node];
    nd.box.min = m_nodes[nd.left].box.min.cwiseMin(m_nodes[nd.right].box.min);
    nd.box.max = m_nodes[nd.left].box.max.cwiseMax(m_nodes[nd.right].box.max);
  }
}

int Bvh::depth() const {
  if (m_count == 0) return 0;
  int deepest = 0;
  std::vector<std::pair<int, int>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [node, level] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, level);
    if (!isLeaf(node)) {
      stack.push_back({m_nodes[node].left, level + 1});
      stack.push_back({m_nodes[node].right, level + 1});
    }
  }
  return deepest;
}

}  // namespace drape::collision
