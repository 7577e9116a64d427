// Static stencils of an energy (triangles, hinges) with the two assembly speed-ups of newton-drape-pizana
// section 6: a stencil -> 3x3 block slot map of the static matrix pattern (6.1), and a greedy colouring of the
// stencils (no two stencils of one colour share a vertex) so that one colour is assembled in parallel without
// atomics, colours in sequence (6.5).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "drape/newton/block_matrix.h"

namespace drape::newton {

// Requests every cache line of [p, p + bytes) ahead of its use. On a reordered (RCM) matrix the passes visit the
// stencils by storage row (StencilSet::prepare), not by index, so per-stencil data indexed by stencil does not
// stream and the hardware does not foresee its reads.
inline void prefetchRange(const void* p, std::size_t bytes) {
  const char* c = static_cast<const char*>(p);
  for (std::size_t o = 0; o < bytes; o += 64) __builtin_prefetch(c + o);
  __builtin_prefetch(c + bytes - 1);
}
// How many stencils ahead a per-stencil Hessian pass requests its data.
inline constexpr int kPrefetchAhead = 4;

// N vertices per stencil (3: triangle, 4: hinge).
template <int N>
class StencilSet {
 public:
  using Stencil = std::array<int, N>;
  static constexpr int kPairs = N * (N + 1) / 2;  // blocks (a, b), a <= b, of one stencil

  StencilSet() = default;
  // Colours the stencils greedily in index order. Vertex indices must be >= 0.
  explicit StencilSet(std::vector<Stencil> stencils);

  int size() const { return static_cast<int>(m_stencils.size()); }
  const Stencil& operator[](int s) const { return m_stencils[s]; }
  int numColours() const { return static_cast<int>(m_colours.size()); }
  // Stencil indices of colour c (ascending, or in storage-row order after prepare on an RCM matrix); no two share
  // a vertex.
  const std::vector<int>& colour(int c) const { return m_colours[c]; }

  // Calls body(indices, count) on chunks of stencil indices covering every stencil once. Serial: one chunk,
  // index order (bitwise the order of a plain loop; storage-row order after prepare on an RCM matrix).
  // Parallel, so bodies that write only to their stencil's vertices never race: when the serial order is local
  // (neighbouring stencils share vertices, as on a Hilbert-numbered mesh or an RCM matrix), contiguous runs of
  // the serial order ("chunks") coloured so that chunks of one colour share no vertex, colours in sequence and
  // chunks of one colour on TBB threads; every thread then walks memory in order. Otherwise the per-stencil
  // colouring, colour by colour.
  void forEach(bool parallel, const std::function<void(const int* indices, int count)>& body) const;
  // Number of chunk colours of the parallel schedule (0: the per-stencil colouring is used), and the chunks
  // of one chunk colour as [begin, end) ranges of the serial order (exposed for tests).
  int numChunkColours() const { return static_cast<int>(m_chunkColours.size()); }
  std::vector<std::pair<int, int>> chunkRanges(int chunkColour) const;
  const std::vector<int>& serialOrder() const { return m_serialOrder; }

  // Makes the slot map valid for h's pattern (rebuilt only when h.patternId() changed) and, when h is reordered
  // (RCM), sorts each colour and the serial order by the stencils' first storage row (locality of the writes).
  // Not thread-safe: call before a parallel forEach that uses addHessian with cached = true.
  void prepare(const BlockMatrix& h) const;

  // Adds the upper block triangle of a stencil Hessian he (3N x 3N, ordered as the stencil's vertices) to h:
  // H(va, vb) += he_ab and H(vb, va) += he_ab^T for a < b, H(va, va) += he_aa. cached: through the slot map
  // (prepare first); otherwise through BlockMatrix::addBlock (binary search per block).
  void addHessian(int s, const Eigen::Matrix<double, 3 * N, 3 * N>& he, BlockMatrix& h, bool cached) const;
  // The same from the blocks (a, b), a <= b, of he in pair order ((0, 0), (0, 1), ..., (1, 1), ...).
  void addPairBlocks(int s, const std::array<Eigen::Matrix3d, kPairs>& blocks, BlockMatrix& h, bool cached) const;
  // The same for he = a u u^T + b w w^T (u, w: 3N), block by block without forming he (hinge bending's Gauss-Newton
  // Hessian with its folded dissipation's): a tenth of the arithmetic and no 3N x 3N temporaries.
  void addOuterProducts(int s, double a, const Eigen::Matrix<double, 3 * N, 1>& u, double b,
                        const Eigen::Matrix<double, 3 * N, 1>& w, BlockMatrix& h, bool cached) const;
  // g(3 v_a .. 3 v_a + 2) += ge(3a .. 3a + 2).
  void addGradient(int s, const Eigen::Matrix<double, 3 * N, 1>& ge, Eigen::VectorXd& g) const;
  // Requests stencil s's vertices and block slots ahead of a Hessian pass's visit (prefetchRange).
  void prefetch(int s) const {
    prefetchRange(&m_stencils[s], sizeof(Stencil));
    if (static_cast<size_t>(s) < m_slots.size()) prefetchRange(&m_slots[s], sizeof(m_slots[s]));
  }
  // Appends the vertex pairs (v_a, v_b), a < b, of every stencil (static couplings).
  void addCouplings(std::vector<std::pair<int, int>>& pairs) const;

 private:
  std::vector<Stencil> m_stencils;
  mutable std::vector<int> m_serialOrder;           // 0 .. size-1 (by storage row after prepare on an RCM matrix)
  mutable std::vector<std::vector<int>> m_colours;  // ascending (by storage row after prepare on an RCM matrix)
  mutable std::vector<std::array<int, 2 * kPairs>> m_slots;  // per stencil and pair: (a, b) and (b, a) slots
  mutable std::vector<int> m_chunkStart;                     // chunk c: m_serialOrder[start[c] .. start[c + 1])
  mutable std::vector<std::vector<int>> m_chunkColours;      // chunks of each colour; empty: no chunk schedule

  // Adds block (a, b) = blk of stencil s (and its transpose at (b, a), a < b), pair index p of (a, b).
  void addPairBlock(int s, int a, int b, int p, const Eigen::Matrix3d& blk, BlockMatrix& h, bool cached) const;
  // Rebuilds the chunk schedule from the rows the stencils' vertices map to; sortByRow first sorts the serial
  // order and the colours by each stencil's first row (ties by index).
  void scheduleChunks(const std::function<int(int vertex)>& row, bool sortByRow) const;
  mutable long m_patternId = -1;
};

extern template class StencilSet<3>;
extern template class StencilSet<4>;

}  // namespace drape::newton
