#pragma once
// The collision-aware global solve by a direct factorisation (solver.preview.contact_solve = factor): eq. 14
//   (K + Delta K) x = b + S^T W p,   Delta K = S^T W S diagonal on the colliding DOFs,
// solved with a CHOLMOD Cholesky factor of K + Delta K. The fill-reducing ordering and symbolic analysis of K are
// computed once (Delta K only adds to K's diagonal, so the pattern never changes). When the contact DOFs or weights
// change between calls by at most maxUpdates(n) DOFs, the factor is modified by CHOLMOD's rank-k update (DOFs that
// joined, or whose weight grew) and downdate (left, or weight shrank), otherwise refactorised; every call is then a
// pair of triangular solves for the three coordinates. Exact up to rounding, unlike the dual + PCG solves of
// contact_solve.h, and at a few thousand DOFs far cheaper than their tens of collision-free solves per L-G iteration;
// the domain decomposition is not used (one factor, CHOLMOD's own ordering).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <vector>

#include "drape/pd/contact_solve.h"

namespace drape::pd {

class ContactFactor {
 public:
  // k: the collision-free matrix K (|free| x |free|, symmetric positive definite); kept by reference.
  explicit ContactFactor(const Eigen::SparseMatrix<double>& k);
  ~ContactFactor();
  ContactFactor(const ContactFactor&) = delete;
  ContactFactor& operator=(const ContactFactor&) = delete;

  // x: on entry the collision-free solution K^-1 b (|free| x 3); on exit the solution of eq. 14 with `contacts`.
  // b: that right-hand side when the caller has it (the product K x is then not formed again); nullptr: K x.
  // Returns false (x unchanged) if K + Delta K is not numerically positive definite.
  bool solve(const ContactSet& contacts, Eigen::MatrixX3d& x, const Eigen::MatrixX3d* b = nullptr);
  int factorisations() const { return m_factorisations; }  // numeric factorisations so far
  int updates() const { return m_updates; }                // calls that modified the factor by update/downdate
  // Changed DOFs up to which the factor of an n x n K is updated rather than refactorised: 64, or n / 32 on larger
  // systems. An update costs about a path of the elimination tree per changed DOF, a refactorisation the whole
  // factor; on a 10k-vertex garment a refactorisation costs as much as several hundred changed DOFs' updates, so a
  // fixed 64 sent the assembly's large changes to refactorisations (docs/BENCHMARKS.md, "Local step and contact
  // solve").
  static int maxUpdates(int n) { return n / 32 > 64 ? n / 32 : 64; }

 private:
  struct Cholmod;
  const Eigen::SparseMatrix<double>& m_k;
  std::unique_ptr<Cholmod> m_cholmod;
  // Brings the factor from the current weights (m_weight) to `weight` (per DOF, N/m) by update/downdate; false if
  // too many DOFs changed or CHOLMOD failed (the caller refactorises).
  bool updateFactor(const std::vector<double>& weight);
  std::vector<double> m_weight;   // per DOF: contact weight in the current factor (0 = none)
  std::vector<double> m_next;     // per DOF: weight asked for by the current call
  bool m_factored = false;
  int m_factorisations = 0;
  int m_updates = 0;
};

}  // namespace drape::pd
