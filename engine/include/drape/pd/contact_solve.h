#pragma once
// Contact constraints and the collision-aware global solve of pd-dd section 6. Each contact constraint acts on
// one vertex with A_k = I (as the paper, following Lan et al. 2024), so Delta K is diagonal on the colliding
// DOFs. After the collision-free solve x = K^-1 b, eq. 14 (K + Delta K) dx = Delta b - Delta K x is solved:
//   DualThenPcg: the closed-form steepest-descent step of the dual problem (eq. 24, eps_k = K_kk / w_k) moves
//                the colliding DOFs by (p_k - x_k) / (1 + eps_k); one collision-free solve spreads the remaining
//                force to the other DOFs; PCG on eq. 14 preconditioned by K^-1 (the DD solve) finishes.
//   Pcg:         PCG on eq. 14 from dx = 0 with the same preconditioner (baseline).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "drape/pd/global_solver.h"
#include "drape/pd/preview_settings.h"

namespace drape::pd {

// Active contacts over the free DOFs: dofs[k] is pulled towards targets.row(k) with weight weights[k] (N/m).
// A DOF may appear once.
struct ContactSet {
  std::vector<int> dofs;
  Eigen::MatrixX3d targets;
  std::vector<double> weights;
  int size() const { return static_cast<int>(dofs.size()); }
};

struct ContactSolveStats {
  int sdIterations = 0;
  int pcgIterations = 0;
  double relativeResidual = 0.0;  // |r| / |r_0| of eq. 14 at exit
};

// x: on entry the collision-free solution K^-1 b (|free| x 3); on exit the solution of (K + Delta K) x =
// b + Delta b (up to the PCG tolerance / iteration cap). k: the matrix `solver` inverts.
ContactSolveStats solveWithContacts(const Eigen::SparseMatrix<double>& k, const GlobalSolver& solver,
                                    const ContactSet& contacts, ContactSolveKind kind, int maxPcgIterations,
                                    double pcgTolerance, Eigen::MatrixX3d& x);

}  // namespace drape::pd
