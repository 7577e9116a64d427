#include "drape/pd/contact_factor.h"

#include <cholmod.h>
#include <tbb/parallel_invoke.h>

#include <array>
#include <cmath>

namespace drape::pd {
namespace {

// Columns [first, first + C) of X = A^-1 B for A = P^T L D L^T P, with L the unit lower triangular factor of a
// simplicial LDL^T CHOLMOD factor (D on its diagonal, each column's entries sorted, the diagonal first; columns may
// be unpacked after updates: nz counts the used entries). b, x: n x 3, column-major. The C columns go through L
// together, so L is read once per pass for them.
template <int C>
void solveLdlColumns(const cholmod_factor& factor, const double* b, double* x, int first) {
  const int n = static_cast<int>(factor.n);
  const int* colStart = static_cast<const int*>(factor.p);
  const int* count = static_cast<const int*>(factor.nz);
  const int* row = static_cast<const int*>(factor.i);
  const double* value = static_cast<const double*>(factor.x);
  const int* perm = static_cast<const int*>(factor.Perm);
  std::vector<std::array<double, C>> y(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < C; ++c) y[k][c] = b[static_cast<size_t>(first + c) * n + perm[k]];
  for (int j = 0; j < n; ++j) {  // L y = P b
    const std::array<double, C> yj = y[j];
    for (int p = colStart[j] + 1; p < colStart[j] + count[j]; ++p)
      for (int c = 0; c < C; ++c) y[row[p]][c] -= value[p] * yj[c];
  }
  for (int j = 0; j < n; ++j)  // D
    for (int c = 0; c < C; ++c) y[j][c] /= value[colStart[j]];
  for (int j = n - 1; j >= 0; --j) {  // L^T z = y
    std::array<double, C> s = y[j];
    for (int p = colStart[j] + 1; p < colStart[j] + count[j]; ++p)
      for (int c = 0; c < C; ++c) s[c] -= value[p] * y[row[p]][c];
    y[j] = s;
  }
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < C; ++c) x[static_cast<size_t>(first + c) * n + perm[k]] = y[k][c];
}

}  // namespace

// CHOLMOD state: K + Delta K's lower triangle (values refreshed in place), its factor and workspace.
struct ContactFactor::Cholmod {
  cholmod_common common{};
  Eigen::SparseMatrix<double> lower;  // lower triangle of K, then of K + Delta K
  std::vector<int> diagonal;          // per column: index of the diagonal entry in lower's values
  Eigen::VectorXd kDiagonal;          // K's diagonal
  cholmod_sparse view{};
  cholmod_factor* factor = nullptr;
  cholmod_dense* rhs = nullptr;
  Cholmod() { cholmod_start(&common); }
  ~Cholmod() {
    if (factor) cholmod_free_factor(&factor, &common);
    if (rhs) cholmod_free_dense(&rhs, &common);
    cholmod_finish(&common);
  }
};

ContactFactor::ContactFactor(const Eigen::SparseMatrix<double>& k) : m_k(k), m_cholmod(std::make_unique<Cholmod>()) {
  Cholmod& c = *m_cholmod;
  const int n = static_cast<int>(k.rows());
  c.lower = k.triangularView<Eigen::Lower>();
  c.lower.makeCompressed();
  c.diagonal.assign(n, -1);
  c.kDiagonal = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < n; ++j)
    for (int p = c.lower.outerIndexPtr()[j]; p < c.lower.outerIndexPtr()[j + 1]; ++p)
      if (c.lower.innerIndexPtr()[p] == j) {
        c.diagonal[j] = p;
        c.kDiagonal[j] = c.lower.valuePtr()[p];
      }
  cholmod_sparse& v = c.view;
  v.nrow = v.ncol = static_cast<size_t>(n);
  v.nzmax = static_cast<size_t>(c.lower.nonZeros());
  v.p = c.lower.outerIndexPtr();
  v.i = c.lower.innerIndexPtr();
  v.x = c.lower.valuePtr();
  v.stype = -1;
  v.itype = CHOLMOD_INT;
  v.xtype = CHOLMOD_REAL;
  v.dtype = CHOLMOD_DOUBLE;
  v.sorted = 1;
  v.packed = 1;
  c.common.print = 0;
  c.common.supernodal = CHOLMOD_SIMPLICIAL;  // no BLAS threads competing with TBB at these sizes
  c.factor = cholmod_analyze(&v, &c.common);
  c.rhs = cholmod_allocate_dense(static_cast<size_t>(n), 3, static_cast<size_t>(n), CHOLMOD_REAL, &c.common);
}

ContactFactor::~ContactFactor() = default;

bool ContactFactor::updateFactor(const std::vector<double>& weight) {
  Cholmod& c = *m_cholmod;
  const int n = static_cast<int>(weight.size());
  std::vector<int> up, down;
  for (int d = 0; d < n; ++d) {
    if (weight[d] > m_weight[d]) up.push_back(d);
    else if (weight[d] < m_weight[d]) down.push_back(d);
    if (static_cast<int>(up.size() + down.size()) > maxUpdates(n)) return false;
  }
  // L L^T = P A P^T: the columns of C (sqrt(|dw|) e_d) are given in the factor's permuted row order.
  const int* perm = static_cast<const int*>(c.factor->Perm);
  std::vector<int> position(n);
  for (int k = 0; k < n; ++k) position[perm[k]] = k;
  const auto apply = [&](const std::vector<int>& dofs, int update) {
    if (dofs.empty()) return true;
    const size_t m = dofs.size();
    cholmod_sparse* cs = cholmod_allocate_sparse(static_cast<size_t>(n), m, m, 1, 1, 0, CHOLMOD_REAL, &c.common);
    if (!cs) return false;
    int* colStart = static_cast<int*>(cs->p);
    int* row = static_cast<int*>(cs->i);
    double* value = static_cast<double*>(cs->x);
    for (size_t k = 0; k < m; ++k) {
      colStart[k] = static_cast<int>(k);
      row[k] = position[dofs[k]];
      value[k] = std::sqrt(std::abs(weight[dofs[k]] - m_weight[dofs[k]]));
    }
    colStart[m] = static_cast<int>(m);
    const bool ok = cholmod_updown(update, cs, c.factor, &c.common) != 0 && c.factor->minor == c.factor->n;
    cholmod_free_sparse(&cs, &c.common);
    return ok;
  };
  if (!apply(up, 1) || !apply(down, 0)) return false;
  return true;
}

bool ContactFactor::solve(const ContactSet& contacts, Eigen::MatrixX3d& x, const Eigen::MatrixX3d* b) {
  Cholmod& c = *m_cholmod;
  const int n = static_cast<int>(m_k.rows());
  if (!c.factor || !c.rhs || x.rows() != n) return false;
  if (contacts.size() == 0 && !m_factored) return true;  // x = K^-1 b already
  for (int d : contacts.dofs)
    if (d < 0 || d >= n || c.diagonal[d] < 0) return false;
  m_next.assign(n, 0.0);
  for (int k = 0; k < contacts.size(); ++k) m_next[contacts.dofs[k]] = contacts.weights[k];
  if (m_weight.size() != static_cast<size_t>(n)) m_weight.assign(n, 0.0);
  if (!m_factored || m_next != m_weight) {
    if (m_factored && updateFactor(m_next)) {
      ++m_updates;
    } else {
      double* value = c.lower.valuePtr();
      for (int d = 0; d < n; ++d) value[c.diagonal[d]] = c.kDiagonal[d] + m_next[d];
      m_factored = cholmod_factorize(&c.view, c.factor, &c.common) != 0 && c.factor->minor == c.factor->n;
      ++m_factorisations;
      if (!m_factored) {
        m_weight.assign(n, 0.0);
        return false;
      }
    }
    m_weight.swap(m_next);
  }
  // Right-hand side b + S^T W p (b = K x when not given: x = K^-1 b on entry), column-major n x 3.
  Eigen::Map<Eigen::MatrixXd> rhs(static_cast<double*>(c.rhs->x), n, 3);
  if (b && b->rows() == n)
    rhs = *b;
  else
    rhs.noalias() = m_k * x;
  for (int k = 0; k < contacts.size(); ++k)
    rhs.row(contacts.dofs[k]) += contacts.weights[k] * contacts.targets.row(k);
  // The three coordinates' triangular solves on two threads (x and y on one, z on the other): the factor is only
  // read, and this serial phase otherwise leaves the second core idle. The simplicial analysis and the updates
  // keep an LDL^T factor; any other kind goes through cholmod_solve.
  const cholmod_factor& f = *c.factor;
  Eigen::MatrixXd out(n, 3);
  if (!f.is_super && !f.is_ll && f.xtype == CHOLMOD_REAL) {
    const double* in = rhs.data();
    tbb::parallel_invoke([&] { solveLdlColumns<2>(f, in, out.data(), 0); },
                         [&] { solveLdlColumns<1>(f, in, out.data(), 2); });
  } else {
    cholmod_dense* sol = cholmod_solve(CHOLMOD_A, c.factor, c.rhs, &c.common);
    if (!sol) return false;
    out = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(sol->x), n, 3);
    cholmod_free_dense(&sol, &c.common);
  }
  const bool finite = out.allFinite();
  if (finite) x = out;
  return finite;
}

}  // namespace drape::pd
