// Linear solves of the Newton step (newton-drape-pizana 3.1.1, 6.2, 6.3): PCG on the block matrix with a choice
// of preconditioner, optionally in single precision, or a CHOLMOD direct solve as a reference.
#pragma once

#include "drape/newton/block_matrix.h"

namespace drape::newton {

enum class Preconditioner { None, Diagonal, BlockJacobi, IncompleteCholesky };
enum class LinearSolverKind { Pcg, Cholmod };

struct LinearSolveOptions {
  LinearSolverKind kind = LinearSolverKind::Pcg;
  Preconditioner preconditioner = Preconditioner::BlockJacobi;
  double tolerance = 1e-2;   // relative residual |Ax - b| / |b| (tau_cg)
  int maxIterations = 500;
  bool mixedPrecision = false;  // PCG in float (matrix, vectors, preconditioner), derivatives stay double
};

struct LinearSolveResult {
  int iterations = 0;             // PCG iterations (0 for the direct solve)
  double relativeResidual = 0.0;  // |Ax - b| / |b| of the returned x, computed in double
  bool ok = false;                // false on a failed factorisation or non-finite result
};

// Solves A x = b for the SPD block matrix A (static + dynamic parts). x is overwritten (size of b).
LinearSolveResult solveLinear(const BlockMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                              const LinearSolveOptions& options);

}  // namespace drape::newton
