#include "drape/newton/stencil_set.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <numeric>
#include <vector>

namespace drape::newton {
namespace {

constexpr int kNoTranspose = -2;  // slot of (b, a) when v_a == v_b: the block is added once, untransposed
constexpr int kGrain = 64;        // stencils per parallel chunk

}  // namespace

template <int N>
StencilSet<N>::StencilSet(std::vector<Stencil> stencils) : m_stencils(std::move(stencils)) {
  m_serialOrder.resize(m_stencils.size());
  std::iota(m_serialOrder.begin(), m_serialOrder.end(), 0);
  // Greedy colouring: each stencil takes the lowest colour unused by any stencil sharing one of its vertices.
  int maxVertex = -1;
  for (const auto& st : m_stencils)
    for (int v : st) maxVertex = std::max(maxVertex, v);
  std::vector<std::vector<int>> vertexColours(maxVertex + 1);
  std::vector<char> used;
  for (int s = 0; s < size(); ++s) {
    used.assign(m_colours.size() + 1, 0);
    for (int v : m_stencils[s])
      for (int c : vertexColours[v]) used[c] = 1;
    const int c = static_cast<int>(std::find(used.begin(), used.end(), 0) - used.begin());
    if (c == numColours()) m_colours.emplace_back();
    m_colours[c].push_back(s);
    for (int v : m_stencils[s])
      if (vertexColours[v].empty() || vertexColours[v].back() != c) vertexColours[v].push_back(c);
  }
}

template <int N>
void StencilSet<N>::forEach(bool parallel, const std::function<void(const int*, int)>& body) const {
  if (!parallel) {
    if (size() > 0) body(m_serialOrder.data(), size());
    return;
  }
  for (const auto& ids : m_colours) {
    const int n = static_cast<int>(ids.size());
    if (n <= kGrain) {
      body(ids.data(), n);
      continue;
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, n, kGrain), [&](const tbb::blocked_range<int>& r) {
      body(ids.data() + r.begin(), static_cast<int>(r.size()));
    });
  }
}

template <int N>
void StencilSet<N>::prepare(const BlockMatrix& h) const {
  if (m_patternId == h.patternId() && m_slots.size() == m_stencils.size()) return;
  m_slots.resize(m_stencils.size());
  for (int s = 0; s < size(); ++s) {
    const Stencil& st = m_stencils[s];
    int p = 0;
    for (int a = 0; a < N; ++a)
      for (int b = a; b < N; ++b, ++p) {
        m_slots[s][2 * p] = h.findBlock(st[a], st[b]);
        m_slots[s][2 * p + 1] = st[a] == st[b] ? kNoTranspose : h.findBlock(st[b], st[a]);
      }
  }
  m_patternId = h.patternId();
  // Locality (6.4): on a reordered (RCM) matrix, visit the stencils of a colour, and the serial order, by their
  // first storage row, so that consecutive stencils write neighbouring blocks; otherwise in index order.
  std::vector<int> key(m_stencils.size());
  for (int s = 0; s < size(); ++s) {
    key[s] = s;
    if (h.reordered()) {
      key[s] = h.internalIndex(m_stencils[s][0]);
      for (int v : m_stencils[s]) key[s] = std::min(key[s], h.internalIndex(v));
    }
  }
  auto byKey = [&key](int a, int b) { return key[a] < key[b] || (key[a] == key[b] && a < b); };
  std::sort(m_serialOrder.begin(), m_serialOrder.end(), byKey);
  for (auto& ids : m_colours) std::sort(ids.begin(), ids.end(), byKey);
}

template <int N>
void StencilSet<N>::addHessian(int s, const Eigen::Matrix<double, 3 * N, 3 * N>& he, BlockMatrix& h,
                               bool cached) const {
  const Stencil& st = m_stencils[s];
  if (!cached) {
    for (int a = 0; a < N; ++a)
      for (int b = a; b < N; ++b) h.addBlock(st[a], st[b], he.template block<3, 3>(3 * a, 3 * b));
    return;
  }
  const auto& slots = m_slots[s];
  int p = 0;
  for (int a = 0; a < N; ++a)
    for (int b = a; b < N; ++b, ++p) {
      const int k = slots[2 * p], kt = slots[2 * p + 1];
      if (k < 0) {  // outside the static pattern: dynamic part, as addBlock would do
        h.addBlock(st[a], st[b], he.template block<3, 3>(3 * a, 3 * b));
        continue;
      }
      h.blockAt(k) += he.template block<3, 3>(3 * a, 3 * b);
      if (kt != kNoTranspose) h.blockAt(kt) += he.template block<3, 3>(3 * a, 3 * b).transpose();
    }
}

template <int N>
void StencilSet<N>::addGradient(int s, const Eigen::Matrix<double, 3 * N, 1>& ge, Eigen::VectorXd& g) const {
  const Stencil& st = m_stencils[s];
  for (int a = 0; a < N; ++a) g.template segment<3>(3 * st[a]) += ge.template segment<3>(3 * a);
}

template <int N>
void StencilSet<N>::addCouplings(std::vector<std::pair<int, int>>& pairs) const {
  for (const auto& st : m_stencils)
    for (int a = 0; a < N; ++a)
      for (int b = a + 1; b < N; ++b) pairs.emplace_back(st[a], st[b]);
}

template class StencilSet<3>;
template class StencilSet<4>;

}  // namespace drape::newton
