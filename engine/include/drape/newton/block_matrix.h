// Symmetric sparse matrix of 3x3 blocks for the Newton drape solver (newton-drape-pizana section 6.1):
// a static-topology part whose block pattern is built once (CSR of 3x3 blocks, both triangles stored) and a
// small dynamic part for contact blocks that change every step. The product is the sum of both parts.
// Optionally the block rows are stored in a Reverse Cuthill-McKee order (section 6.4): callers keep using vertex
// indices everywhere; only the storage (and the *Internal kernels of the linear solver) see the permutation.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <mutex>
#include <utility>
#include <vector>

namespace drape::newton {

// Matrix of numBlocks x numBlocks blocks, each 3x3, i.e. 3|V| x 3|V| scalars acting on flat position vectors
// (x0, y0, z0, x1, ...). Symmetric by construction: addBlock(i, j, B) stores B at (i, j) and B^T at (j, i).
class BlockMatrix {
 public:
  BlockMatrix() = default;
  // Builds the static pattern: every diagonal block plus (i, j) and (j, i) for each listed vertex pair.
  // Pairs may repeat and come in either order; pairs with i == j are ignored (the diagonal is always there).
  BlockMatrix(int numBlocks, const std::vector<std::pair<int, int>>& couplings, bool reorder = false);

  // Rebuilds the static pattern (values zero, dynamic part empty). reorder: store block rows in the RCM order of
  // the coupling graph (dof_ordering.h) instead of vertex order.
  void build(int numBlocks, const std::vector<std::pair<int, int>>& couplings, bool reorder = false);

  // Number of 3x3 block rows (= |V|) and scalar rows (= 3|V|).
  int numBlocks() const { return m_numBlocks; }
  int size() const { return 3 * m_numBlocks; }
  // Number of stored static blocks (both triangles and the diagonal) and of dynamic entries this step.
  int staticBlockCount() const { return static_cast<int>(m_blocks.size()); }
  int dynamicBlockCount() const { return static_cast<int>(m_dynamic.size()); }

  // Zeroes every static value (pattern kept) and clears the dynamic part.
  void setZero();
  // Replaces every static value by values (a copy of blocks() taken on this pattern) and clears the dynamic part:
  // restores a saved part of the matrix (the Newton solver's reused Hessian). Throws std::invalid_argument on a
  // size mismatch.
  void setStaticValues(const std::vector<Eigen::Matrix3d>& values);

  // Hessian accumulation: H_ij += b and, when i != j, H_ji += b^T. Call once per unordered pair and stencil.
  // Pairs in the static pattern go there (thread-safe when no two threads touch the same block, e.g. with
  // stencil colouring); pairs outside it go to the dynamic part (always thread-safe, takes a lock).
  void addBlock(int i, int j, const Eigen::Matrix3d& b);
  // Adds to the dynamic part regardless of the static pattern (contacts). Thread-safe.
  void addDynamicBlock(int i, int j, const Eigen::Matrix3d& b);

  // Index of static block (i, j) in blockAt(), or -1 when the pair is not in the static pattern. Lets an energy
  // precompute its stencil -> block map once (section 6.1) and then write through blockAt(k) directly.
  int findBlock(int i, int j) const;
  Eigen::Matrix3d& blockAt(int k) { return m_blocks[k]; }
  const Eigen::Matrix3d& blockAt(int k) const { return m_blocks[k]; }

  // Diagonal block H_ii (static part only; the dynamic part is not included).
  Eigen::Matrix3d& diagonalBlock(int i) { return m_blocks[m_diag[internalIndex(i)]]; }
  const Eigen::Matrix3d& diagonalBlock(int i) const { return m_blocks[m_diag[internalIndex(i)]]; }
  // Diagonal block including the dynamic part's contributions to (i, i) (for preconditioners).
  Eigen::Matrix3d fullDiagonalBlock(int i) const;

  // y = H x with H = static + dynamic. x and y have size 3|V|; y is overwritten. Parallel over block rows.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  Eigen::VectorXd operator*(const Eigen::VectorXd& x) const;

  // The whole matrix (static + dynamic) as an Eigen sparse matrix, 3|V| x 3|V|, for tests and direct solves.
  Eigen::SparseMatrix<double> toSparse() const;

  // CSR access to the static pattern in storage numbering (see internalIndex).
  int rowStart(int i) const { return m_rowStart[i]; }
  // Storage ("internal") numbering of the block rows: internalIndex(vertex) is the storage row of a vertex and
  // originalIndex(row) the vertex stored there; both the identity unless built with reorder.
  bool reordered() const { return !m_position.empty(); }
  int internalIndex(int i) const { return m_position.empty() ? i : m_position[i]; }
  int originalIndex(int r) const { return m_order.empty() ? r : m_order[r]; }
  // Flat vector (3|V|) from vertex order to storage order and back; out is resized.
  template <typename Vec>
  void toInternal(const Vec& x, Vec& out) const;
  template <typename Vec>
  void toOriginal(const Vec& x, Vec& out) const;
  // Static blocks in storage order: row r (storage numbering) spans [rowStart(r), rowStart(r+1)) of blocks(),
  // with storage column colIndex(k).
  const std::vector<Eigen::Matrix3d>& blocks() const { return m_blocks; }
  const int* rowStarts() const { return m_rowStart.data(); }
  const int* colIndices() const { return m_cols.data(); }
  // Largest |row - column| over the stored blocks (block bandwidth of the storage numbering).
  int bandwidth() const;

  // Identifier of the current static pattern, unique per build() in the process: a cached stencil -> block map
  // made for one pattern is valid exactly while patternId() is unchanged.
  long patternId() const { return m_patternId; }
  int colIndex(int k) const { return m_cols[k]; }

  // One dynamic entry: H_ij += block (and H_ji += block^T when i != j).
  struct DynamicEntry {
    int i = 0;
    int j = 0;
    Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
  };
  const std::vector<DynamicEntry>& dynamicEntries() const { return m_dynamic; }

 private:
  int m_numBlocks = 0;
  long m_patternId = -1;
  std::vector<int> m_rowStart;         // numBlocks + 1
  std::vector<int> m_cols;             // sorted per row
  std::vector<int> m_diag;             // index of (r, r) per storage row
  std::vector<int> m_order;            // storage row -> vertex (empty: identity)
  std::vector<int> m_position;         // vertex -> storage row (empty: identity)
  std::vector<Eigen::Matrix3d> m_blocks;
  std::vector<DynamicEntry> m_dynamic;
  std::mutex m_dynamicMutex;
};

template <typename Vec>
void BlockMatrix::toInternal(const Vec& x, Vec& out) const {
  out.resize(x.size());
  if (!reordered()) {
    out = x;
    return;
  }
  for (int r = 0; r < m_numBlocks; ++r) out.template segment<3>(3 * r) = x.template segment<3>(3 * m_order[r]);
}

template <typename Vec>
void BlockMatrix::toOriginal(const Vec& x, Vec& out) const {
  out.resize(x.size());
  if (!reordered()) {
    out = x;
    return;
  }
  for (int r = 0; r < m_numBlocks; ++r) out.template segment<3>(3 * m_order[r]) = x.template segment<3>(3 * r);
}

}  // namespace drape::newton
