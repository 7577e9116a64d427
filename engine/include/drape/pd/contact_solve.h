#pragma once
// Contact constraints and the collision-aware global solve of pd-dd section 6. Each contact constraint acts on
// one vertex with A_k = I (as the paper, following Lan et al. 2024), so Delta K = S^T W S is diagonal on the
// colliding DOFs (W = diag(w_k)). After the collision-free solve x = K^-1 b, eq. 14
//   (K + Delta K) dx = Delta b - Delta K x = S^T W (p - S x)
// is solved. By the Woodbury identity (eq. 17) dx = K^-1 S^T mu, where the contact forces mu solve the reduced,
// symmetric positive definite dual system (one unknown per colliding DOF and coordinate)
//   A mu = g,   A = W^-1 + S K^-1 S^T,   g = p - S x.                                        (dual of eq. 18)
//   DualThenPcg: steepest descent on the dual from mu = 0 along the eq. 24 direction s = P r, with
//                P = diag(1 / (1 / w_k + 1 / K_kk)) (mu = P g solves the dual exactly when S K^-1 S^T is diagonal,
//                i.e. for isolated contacts), and the exact step length (s^T r) / (s^T A s). Each update costs one
//                collision-free solve (K^-1 S^T s). The full step mu = P g without the line search overshoots by
//                orders of magnitude on dense contact patches, whose DOFs are coupled through K^-1. The dual
//                residual times w_k is the residual of eq. 14. PCG on eq. 14 preconditioned by K^-1 (the DD solve)
//                finishes from dx = K^-1 S^T mu.
//   Pcg:         PCG on eq. 14 from dx = 0 with the same preconditioner (baseline).
//   DualCgThenPcg: conjugate gradients on the same dual system, preconditioned by K_cc, the block of K on the
//                colliding DOFs (a sparse matrix-vector product), then the same PCG. K_cc bounds from above the
//                Schur complement (S K^-1 S^T)^-1 that inverts the dual operator when w_k >> K, so the
//                preconditioned dual operator has eigenvalues >= 1 and, on contact patches, only a few above;
//                eq. 24's diagonal P is the diagonal of the same approximation and leaves the patch's smooth modes
//                (eigenvalues ~ K_kk / lambda_min(K)) to PCG, which converges slowly on them (K^-1 A has the
//                eigenvalues 1 + w_k eig(S K^-1 S^T), spread over 3-4 orders of magnitude for 1e6 N/m contacts
//                on a 1e2-1e3 N/m fabric). The first dual CG update is an SD step along K_cc r.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "drape/pd/global_solver.h"
#include "drape/pd/preview_settings.h"

namespace drape::pd {

// Active contacts over the free DOFs: dofs[k] is pulled towards targets.row(k) with weight weights[k] (N/m).
// A DOF may appear once (ContactAccumulator merges several constraints on one DOF).
struct ContactSet {
  std::vector<int> dofs;
  Eigen::MatrixX3d targets;
  std::vector<double> weights;
  int size() const { return static_cast<int>(dofs.size()); }
};

// Gathers position constraints on free DOFs, several per DOF allowed, and merges them: constraints
// (w_1, p_1), (w_2, p_2) on one DOF are the single constraint (w_1 + w_2, (w_1 p_1 + w_2 p_2) / (w_1 + w_2))
// up to a constant energy. Not thread-safe: fill from one thread.
class ContactAccumulator {
 public:
  explicit ContactAccumulator(int freeCount = 0) { reset(freeCount); }
  // Forgets every constraint; freeCount: number of free DOFs (vertices).
  void reset(int freeCount);
  // dof in [0, freeCount); target in metres; weight > 0, N/m.
  void add(int dof, const Eigen::Vector3d& target, double weight);
  int constraintCount() const { return m_constraints; }  // before merging
  // Merged constraints, in the order their DOFs were first added.
  ContactSet merged() const;

 private:
  std::vector<double> m_weight;                     // per DOF: summed weight (0 = none)
  std::vector<Eigen::Vector3d> m_weightedTarget;    // per DOF: sum w p
  std::vector<int> m_touched;                       // DOFs with a constraint, first-added order
  int m_constraints = 0;
};

// Contact forces mu of the last collision-aware solve, kept per free DOF so that the next solve (the next L-G
// iteration, or the next step) starts from them: dx_0 = K^-1 S^T mu_0 (one collision-free solve), with mu_0 the
// kept force of every DOF still in the set (0 for a new one). The force that holds a garment on the body changes
// little between iterations, so the solve only has to find the change. force: |free| x 3, in the units of K x
// (N); rows of DOFs out of contact are 0.
struct ContactWarmStart {
  Eigen::MatrixX3d force;
  void clear() { force.resize(0, 3); }
};

// DOFs that are in exactly one of previous (DOF list) and current: the contact set's churn between two L-G
// iterations. scratch: per-DOF flags, resized as needed and left all zero.
int contactChurn(const std::vector<int>& previous, const ContactSet& current, std::vector<char>& scratch);

struct ContactSolveStats {
  int sdIterations = 0;             // dual updates (SD or CG), one collision-free solve each
  int pcgIterations = 0;
  double relativeResidual = 0.0;    // |r| / |r_0| of eq. 14 at exit (max over the 3 coordinates)
  double sdRelativeResidual = 0.0;  // the same after the steepest-descent phase (DualThenPcg only)
  double warmRelativeResidual = 1.0;  // |r| / |r_0| (all coordinates) at the warm start (1 without warm start)
};

// x: on entry the collision-free solution K^-1 b (|free| x 3); on exit the solution of (K + Delta K) x =
// b + Delta b (up to the PCG tolerance / iteration cap). k: the matrix `solver` inverts. sdIterations: dual
// steepest-descent updates of DualThenPcg (>= 1); ignored otherwise. maxDualIterations: cap of DualCgThenPcg. warm: null = start from mu = 0 (the paper);
// else start from warm->force (ignored when its size is not |free| x 3, or when it starts further from the
// solution than mu = 0, measured by the residual of eq. 14) and store the solve's contact forces in it.
// The tolerance is relative to the residual of eq. 14 at dx = 0 in both cases.
ContactSolveStats solveWithContacts(const Eigen::SparseMatrix<double>& k, const GlobalSolver& solver,
                                    const ContactSet& contacts, ContactSolveKind kind, int maxPcgIterations,
                                    double pcgTolerance, Eigen::MatrixX3d& x, int sdIterations = 1,
                                    ContactWarmStart* warm = nullptr, int maxDualIterations = 100);

}  // namespace drape::pd
