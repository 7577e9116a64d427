#include "drape/newton/stencil_set.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <numeric>
#include <vector>

namespace drape::newton {
namespace {

constexpr int kNoTranspose = -2;  // slot of (b, a) when v_a == v_b: the block is added once, untransposed
constexpr int kGrain = 64;        // stencils per parallel chunk
// Chunk schedule: chunks per thread, fewest stencils per chunk, and most chunk colours before the per-stencil
// colouring is used instead (a non-local order makes every chunk overlap many others).
constexpr int kChunksPerThread = 8;
constexpr int kMinChunkStencils = 256;
constexpr int kMaxChunkColours = 4;

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
  scheduleChunks([](int v) { return v; }, false);  // index order: local on a Hilbert-numbered mesh
}

template <int N>
void StencilSet<N>::scheduleChunks(const std::function<int(int)>& row, bool sortByRow) const {
  const int n = size();
  std::vector<int> key(n), last(n);
  for (int s = 0; s < n; ++s) {
    key[s] = last[s] = row(m_stencils[s][0]);
    for (int v : m_stencils[s]) {
      key[s] = std::min(key[s], row(v));
      last[s] = std::max(last[s], row(v));
    }
  }
  if (sortByRow) {
    auto byKey = [&key](int a, int b) { return key[a] < key[b] || (key[a] == key[b] && a < b); };
    std::sort(m_serialOrder.begin(), m_serialOrder.end(), byKey);
    for (auto& ids : m_colours) std::sort(ids.begin(), ids.end(), byKey);
  }

  m_chunkStart.clear();
  m_chunkColours.clear();
  const int threads = tbb::this_task_arena::max_concurrency();
  const int chunks = std::min(kChunksPerThread * threads, n / kMinChunkStencils);
  if (threads < 2 || chunks < 2) return;
  // Row range of each chunk; two chunks whose ranges do not overlap share no vertex.
  std::vector<std::pair<int, int>> range(chunks);
  for (int c = 0; c <= chunks; ++c) m_chunkStart.push_back(static_cast<int>(static_cast<long>(n) * c / chunks));
  for (int c = 0; c < chunks; ++c) {
    range[c] = {key[m_serialOrder[m_chunkStart[c]]], -1};
    for (int k = m_chunkStart[c]; k < m_chunkStart[c + 1]; ++k) {
      range[c].first = std::min(range[c].first, key[m_serialOrder[k]]);
      range[c].second = std::max(range[c].second, last[m_serialOrder[k]]);
    }
  }
  // Greedy colouring of the chunks in order: the lowest colour no overlapping chunk has taken.
  std::vector<int> colour(chunks, -1);
  for (int c = 0; c < chunks; ++c) {
    std::vector<char> used(kMaxChunkColours + 1, 0);
    for (int d = 0; d < c; ++d) {
      const bool overlap = range[d].first <= range[c].second && range[c].first <= range[d].second;
      if (overlap) used[colour[d]] = 1;
    }
    colour[c] = static_cast<int>(std::find(used.begin(), used.end(), 0) - used.begin());
    if (colour[c] >= kMaxChunkColours) {  // too many overlaps: no locality, keep the per-stencil colouring
      m_chunkStart.clear();
      m_chunkColours.clear();
      return;
    }
    if (colour[c] == numChunkColours()) m_chunkColours.emplace_back();
    m_chunkColours[colour[c]].push_back(c);
  }
}

template <int N>
std::vector<std::pair<int, int>> StencilSet<N>::chunkRanges(int chunkColour) const {
  std::vector<std::pair<int, int>> ranges;
  for (int c : m_chunkColours[chunkColour]) ranges.emplace_back(m_chunkStart[c], m_chunkStart[c + 1]);
  return ranges;
}

template <int N>
void StencilSet<N>::forEach(bool parallel, const std::function<void(const int*, int)>& body) const {
  if (!parallel) {
    if (size() > 0) body(m_serialOrder.data(), size());
    return;
  }
  if (!m_chunkColours.empty()) {
    for (const auto& chunks : m_chunkColours)
      tbb::parallel_for(0, static_cast<int>(chunks.size()), [&](int k) {
        const int c = chunks[k];
        body(m_serialOrder.data() + m_chunkStart[c], m_chunkStart[c + 1] - m_chunkStart[c]);
      });
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
  // Locality (6.4): on a reordered (RCM) matrix, visit the stencils (serial order, chunks, colours) by their
  // first storage row, so that consecutive stencils write neighbouring blocks.
  if (h.reordered()) scheduleChunks([&h](int v) { return h.internalIndex(v); }, true);
}

template <int N>
void StencilSet<N>::addPairBlock(int s, int a, int b, int p, const Eigen::Matrix3d& blk, BlockMatrix& h,
                                 bool cached) const {
  const Stencil& st = m_stencils[s];
  const int k = cached ? m_slots[s][2 * p] : -1, kt = cached ? m_slots[s][2 * p + 1] : -1;
  if (k < 0) {  // no slot map, or outside the static pattern (dynamic part): addBlock finds the place
    h.addBlock(st[a], st[b], blk);
    return;
  }
  h.blockAt(k) += blk;
  if (kt != kNoTranspose) h.blockAt(kt) += blk.transpose();
}

template <int N>
void StencilSet<N>::addHessian(int s, const Eigen::Matrix<double, 3 * N, 3 * N>& he, BlockMatrix& h,
                               bool cached) const {
  int p = 0;
  for (int a = 0; a < N; ++a)
    for (int b = a; b < N; ++b, ++p) addPairBlock(s, a, b, p, he.template block<3, 3>(3 * a, 3 * b), h, cached);
}

template <int N>
void StencilSet<N>::addPairBlocks(int s, const std::array<Eigen::Matrix3d, kPairs>& blocks, BlockMatrix& h,
                                  bool cached) const {
  int p = 0;
  for (int a = 0; a < N; ++a)
    for (int b = a; b < N; ++b, ++p) addPairBlock(s, a, b, p, blocks[p], h, cached);
}

template <int N>
void StencilSet<N>::addOuterProducts(int s, double a, const Eigen::Matrix<double, 3 * N, 1>& u, double b,
                                     const Eigen::Matrix<double, 3 * N, 1>& w, BlockMatrix& h, bool cached) const {
  int p = 0;
  for (int i = 0; i < N; ++i) {
    const Eigen::Vector3d ui = a * u.template segment<3>(3 * i), wi = b * w.template segment<3>(3 * i);
    for (int j = i; j < N; ++j, ++p) {
      const Eigen::Matrix3d blk =
          ui * u.template segment<3>(3 * j).transpose() + wi * w.template segment<3>(3 * j).transpose();
      addPairBlock(s, i, j, p, blk, h, cached);
    }
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
