#include "drape/pd/sparse_cholesky.h"

#include <algorithm>
#include <cholmod.h>
#include <cstdint>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "drape/pd/subtree_groups.h"

namespace drape::pd {
namespace {

// The two kernels of the triangular solves for three right-hand sides (w row-major, 3 per row), over the entries
// [begin, end) of one row or column of L: (indices, values).
// Row i solved by a dot product with the entries' rows, which are solved already: w_i = (w_i - sum v w_k) / L_ii.
inline void solveByDot(double* w, int i, const int* index, const double* value, int begin, int end,
                       double invDiagonal) {
  double a = w[3 * i], b = w[3 * i + 1], c = w[3 * i + 2];
  for (int q = begin; q < end; ++q) {
    const double* wk = w + 3 * index[q];
    const double v = value[q];
    a -= v * wk[0];
    b -= v * wk[1];
    c -= v * wk[2];
  }
  w[3 * i] = a * invDiagonal;
  w[3 * i + 1] = b * invDiagonal;
  w[3 * i + 2] = c * invDiagonal;
}

// Row i solved (w_i / L_ii, its share already subtracted), then subtracted from the entries' rows: w_k -= v w_i.
inline void solveAndScatter(double* w, int i, const int* index, const double* value, int begin, int end,
                            double invDiagonal) {
  const double a = w[3 * i] * invDiagonal, b = w[3 * i + 1] * invDiagonal, c = w[3 * i + 2] * invDiagonal;
  w[3 * i] = a;
  w[3 * i + 1] = b;
  w[3 * i + 2] = c;
  for (int q = begin; q < end; ++q) {
    double* wk = w + 3 * index[q];
    const double v = value[q];
    wk[0] -= v * a;
    wk[1] -= v * b;
    wk[2] -= v * c;
  }
}

// A column-stored L read by the sequential passes, one column at a time.
struct ColumnsOfL {
  const int* start;
  const int* row;
  const double* value;
  const double* invDiagonal;
  void forward(double* w, int j) const { solveAndScatter(w, j, row, value, start[j] + 1, start[j + 1], invDiagonal[j]); }
  void backward(double* w, int j) const { solveByDot(w, j, row, value, start[j] + 1, start[j + 1], invDiagonal[j]); }
};

}  // namespace

bool SparseCholesky::factor(const Eigen::SparseMatrix<double>& input, CholeskySolve mode) {
  m_groupRows.clear();
  m_topRows.clear();
  m_rowStart.clear();
  m_column.clear();
  m_rowValue.clear();
  m_reached.clear();
  if (mode == CholeskySolve::Sequential) return factorWith(input, -1);
  // Minimum degree gives less fill, nested dissection a more even tree: keep the ordering whose solve is shorter
  // (sequential top plus the largest group of subtrees; the factor is computed twice, once per ordering).
  if (!factorWith(input, CHOLMOD_AMD)) return false;
  SubtreeGroups plan = planSubtrees();
  SparseCholesky nested;
  if (nested.factorWith(input, CHOLMOD_METIS)) {
    SubtreeGroups other = nested.planSubtrees();
    if (other.cost < plan.cost) {
      *this = std::move(nested);
      plan = std::move(other);
    }
  }
  if (!plan.groups.empty()) useSubtrees(std::move(plan));
  return m_ok;
}

bool SparseCholesky::factorWith(const Eigen::SparseMatrix<double>& input, int ordering) {
  m_ok = false;
  m_nonZeros = 0;
  m_n = static_cast<int>(input.rows());
  if (m_n == 0) {
    m_perm.clear();
    m_colStart.assign(1, 0);
    m_ok = true;
    return true;
  }
  Eigen::SparseMatrix<double> a = input;  // compressed copy, int indices as CHOLMOD_INT expects
  a.makeCompressed();
  cholmod_sparse view{};
  view.nrow = view.ncol = static_cast<size_t>(m_n);
  view.nzmax = static_cast<size_t>(a.nonZeros());
  view.p = a.outerIndexPtr();
  view.i = a.innerIndexPtr();
  view.x = a.valuePtr();
  view.stype = -1;  // symmetric, lower triangle used
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;

  cholmod_common common;
  cholmod_start(&common);
  common.supernodal = CHOLMOD_SIMPLICIAL;
  common.final_ll = 1;  // L L^T rather than L D L^T
  common.print = 0;
  if (ordering >= 0) {
    common.nmethods = 1;
    common.method[0].ordering = ordering;
  }
  cholmod_factor* l = cholmod_analyze(&view, &common);
  bool good = l != nullptr;
  if (good) good = cholmod_factorize(&view, l, &common) != 0 && l->minor == l->n && l->is_ll && !l->is_super;
  if (good) {
    const int* p = static_cast<const int*>(l->p);
    const int* i = static_cast<const int*>(l->i);
    const int* nz = static_cast<const int*>(l->nz);
    const double* x = static_cast<const double*>(l->x);
    const int* perm = static_cast<const int*>(l->Perm);
    m_perm.assign(perm, perm + m_n);
    m_colStart.assign(m_n + 1, 0);
    for (int j = 0; j < m_n; ++j) m_colStart[j + 1] = m_colStart[j] + nz[j];
    m_row.resize(m_colStart[m_n]);
    m_value.resize(m_colStart[m_n]);
    m_invDiagonal.resize(m_n);
    for (int j = 0; j < m_n; ++j) {
      std::copy(i + p[j], i + p[j] + nz[j], m_row.begin() + m_colStart[j]);
      std::copy(x + p[j], x + p[j] + nz[j], m_value.begin() + m_colStart[j]);
      // CHOLMOD keeps the diagonal first in each simplicial column.
      good = good && nz[j] > 0 && i[p[j]] == j && x[p[j]] > 0.0;
      if (good) m_invDiagonal[j] = 1.0 / x[p[j]];
    }
    m_nonZeros = static_cast<long>(m_value.size());
  }
  if (l) cholmod_free_factor(&l, &common);
  cholmod_finish(&common);
  m_ok = good;
  return m_ok;
}

SubtreeGroups SparseCholesky::planSubtrees() const {
  const int n = m_n;
  // Elimination tree: the parent of column j is its first row below the diagonal; a column's work is its length.
  std::vector<int> parent(n, -1);
  std::vector<long> cost(n);
  for (int j = 0; j < n; ++j) {
    for (int q = m_colStart[j] + 1; q < m_colStart[j + 1]; ++q)
      if (parent[j] < 0 || m_row[q] < parent[j]) parent[j] = m_row[q];
    cost[j] = m_colStart[j + 1] - m_colStart[j];
  }
  return groupSubtrees(parent, cost, std::min(8, tbb::this_task_arena::max_concurrency()));
}

void SparseCholesky::useSubtrees(SubtreeGroups plan) {
  const int n = m_n;
  m_groupRows = std::move(plan.groups);
  m_topRows = std::move(plan.top);
  // L by rows (strictly lower part): entry (i, j) of column j goes to row i.
  m_rowStart.assign(n + 1, 0);
  for (int j = 0; j < n; ++j)
    for (int q = m_colStart[j] + 1; q < m_colStart[j + 1]; ++q) ++m_rowStart[m_row[q] + 1];
  for (int i = 0; i < n; ++i) m_rowStart[i + 1] += m_rowStart[i];
  m_column.resize(m_rowStart[n]);
  m_rowValue.resize(m_rowStart[n]);
  std::vector<int> fill(m_rowStart.begin(), m_rowStart.end() - 1);
  for (int j = 0; j < n; ++j)
    for (int q = m_colStart[j] + 1; q < m_colStart[j + 1]; ++q) {
      const int k = fill[m_row[q]]++;
      m_column[k] = j;
      m_rowValue[k] = m_value[q];
    }
  m_colStart.clear();
  m_row.clear();
  m_value.clear();
}

void SparseCholesky::solveSubtreeParallel(double* w) const {
  const int* column = m_column.data();
  const double* value = m_rowValue.data();
  // Forward by rows: row i's columns are its descendants (its group, or a group below a top row). Backward by rows
  // in reverse: row i is final once every ancestor has subtracted its share, and then passes its own share on.
  auto forwardRow = [&](int i) {
    solveByDot(w, i, column, value, m_rowStart[i], m_rowStart[i + 1], m_invDiagonal[i]);
  };
  auto backwardRow = [&](int i) {
    solveAndScatter(w, i, column, value, m_rowStart[i], m_rowStart[i + 1], m_invDiagonal[i]);
  };
  const int groups = static_cast<int>(m_groupRows.size());
  tbb::parallel_for(0, groups, [&](int g) {
    for (int i : m_groupRows[g]) forwardRow(i);
  });
  for (int i : m_topRows) forwardRow(i);
  for (auto it = m_topRows.rbegin(); it != m_topRows.rend(); ++it) backwardRow(*it);
  tbb::parallel_for(0, groups, [&](int g) {
    for (auto it = m_groupRows[g].rbegin(); it != m_groupRows[g].rend(); ++it) backwardRow(*it);
  });
}

void SparseCholesky::solveInPlace(double* x, double* w) const {
  const int n = m_n;
  for (int k = 0; k < n; ++k) {
    const double* src = x + 3 * m_perm[k];
    w[3 * k] = src[0];
    w[3 * k + 1] = src[1];
    w[3 * k + 2] = src[2];
  }
  if (m_groupRows.empty())
    solveSequential(w);
  else
    solveSubtreeParallel(w);
  for (int k = 0; k < n; ++k) {
    double* dst = x + 3 * m_perm[k];
    dst[0] = w[3 * k];
    dst[1] = w[3 * k + 1];
    dst[2] = w[3 * k + 2];
  }
}

void SparseCholesky::solveSequential(double* w) const {
  forward(w);
  backward(w);
}

// L by columns, the diagonal entry first: forward L y = w column by column (a scatter), backward L^T z = y a dot
// product per column. The columns visited: [0, n) or a list, ascending for the forward pass.
void SparseCholesky::forward(double* w) const {
  const ColumnsOfL l{m_colStart.data(), m_row.data(), m_value.data(), m_invDiagonal.data()};
  for (int j = 0; j < m_n; ++j) l.forward(w, j);
}

void SparseCholesky::backward(double* w) const {
  const ColumnsOfL l{m_colStart.data(), m_row.data(), m_value.data(), m_invDiagonal.data()};
  for (int j = m_n - 1; j >= 0; --j) l.backward(w, j);
}

// Column j's entries lie in rows below it, its ancestors in the elimination tree (whose parent is the first of
// them): a forward pass carries a row's value to its ancestors only, and a backward pass computes a row from its
// ancestors only. So both passes, restricted to the columns an interface reaches, are exact there.
void SparseCholesky::setInterface(const std::vector<int>& rows) {
  std::vector<std::uint8_t> reached(m_n, 0);
  std::vector<int> position(m_n);
  for (int k = 0; k < m_n; ++k) position[m_perm[k]] = k;
  for (int r : rows) reached[position[r]] = 1;
  m_reached.clear();
  for (int j = 0; j < m_n; ++j) {
    if (!reached[j]) continue;
    m_reached.push_back(j);
    if (m_colStart[j + 1] > m_colStart[j] + 1)
      reached[*std::min_element(m_row.begin() + m_colStart[j] + 1, m_row.begin() + m_colStart[j + 1])] = 1;
  }
}

void SparseCholesky::forwardOverInterface(double* w) const {
  const ColumnsOfL l{m_colStart.data(), m_row.data(), m_value.data(), m_invDiagonal.data()};
  for (int j : m_reached) l.forward(w, j);
}

void SparseCholesky::backwardOverInterface(double* w) const {
  const ColumnsOfL l{m_colStart.data(), m_row.data(), m_value.data(), m_invDiagonal.data()};
  for (auto it = m_reached.rbegin(); it != m_reached.rend(); ++it) l.backward(w, *it);
}

long SparseCholesky::interfaceNonZeros() const {
  long nz = 0;
  for (int j : m_reached) nz += m_colStart[j + 1] - m_colStart[j];
  return nz;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& b) const {
  const int n = m_n, k = static_cast<int>(b.cols());
  Eigen::MatrixXd out(n, k);
  std::vector<double> x(3 * static_cast<size_t>(n)), w(3 * static_cast<size_t>(n));
  for (int c0 = 0; c0 < k; c0 += 3) {
    const int m = std::min(3, k - c0);
    std::fill(x.begin(), x.end(), 0.0);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < m; ++c) x[3 * i + c] = b(i, c0 + c);
    solveInPlace(x.data(), w.data());
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < m; ++c) out(i, c0 + c) = x[3 * i + c];
  }
  return out;
}

}  // namespace drape::pd
