// Linear solves of the Newton step (newton-drape-pizana 3.1.1, 6.2, 6.3): PCG on the block matrix with a choice
// of preconditioner, optionally in single precision, or a CHOLMOD direct solve as a reference.
#pragma once

#include "drape/newton/block_matrix.h"

namespace drape::newton {

class CoarseSpace;
class CoupledGroups;

// In the order of the choices of solver.cg.preconditioner (Settings::choice), which adds cholmod_direct.
enum class Preconditioner { None, Diagonal, BlockJacobi, IncompleteCholesky };
enum class LinearSolverKind { Pcg, Cholmod };

// What the fused PCG derives from a matrix before iterating: the preconditioner's inverse diagonal blocks and, for a
// mixed-precision solve, the float copy of the static blocks. A caller that solves several times with an unchanged
// matrix (the Newton solver reusing its Hessian in place) keeps one, hands it in through LinearSolveOptions::cache
// and sets valid = false whenever the matrix changes; the solves in between skip the preparation.
struct PcgCache {
  bool valid = false;
  Preconditioner preconditioner = Preconditioner::None;  // what the data were made for
  bool mixed = false;
  std::vector<Eigen::Matrix3d> inverse;
  std::vector<Eigen::Matrix<float, 4, 3>> inverseFloat, blocksFloat;  // each column padded to a SIMD packet
};

struct LinearSolveOptions {
  LinearSolverKind kind = LinearSolverKind::Pcg;
  Preconditioner preconditioner = Preconditioner::BlockJacobi;
  double tolerance = 1e-2;   // relative residual |Ax - b| / |b| (tau_cg)
  int maxIterations = 500;
  bool mixedPrecision = false;  // PCG in float (matrix, vectors, preconditioner), derivatives stay double
  // Start PCG from the incoming x (when it has b's size and is finite) instead of 0: the solver hands in the
  // previous step's velocity change. A guess whose multiple closest to the solution (A-norm) is below 1/8, i.e. one
  // pointing against the solution or far too long, is taken with that multiple. The stopping test stays
  // |Ax - b| <= tolerance |b|.
  bool warmStart = true;
  // Fused block PCG in the matrix's storage order (RCM when the matrix is reordered): one pass over the block
  // rows per SpMV (with p.Ap), one fused pass for x, r, z = P r and both dot products, TBB over row chunks with
  // deterministic reductions; float matrix copy for mixedPrecision. false = the plain Eigen-vector PCG.
  // Preconditioners None, Diagonal and BlockJacobi only (IncompleteCholesky always takes the plain path).
  bool fusedKernels = true;
  // Two-level preconditioner (coarse_space.h, factorised for this matrix by the caller): its coarse correction
  // is added to the Diagonal or BlockJacobi preconditioner of the fused PCG; ignored by the other paths. nullptr:
  // one level.
  const CoarseSpace* coarse = nullptr;
  // Coupled groups of this matrix (coupled_groups.h): their rows take the inverse of the group's submatrix instead
  // of block-Jacobi's blocks (fused PCG with BlockJacobi only). nullptr: none.
  const CoupledGroups* coupled = nullptr;
  // Compute LinearSolveResult::relativeResidual (one more product with A, in double). The Newton solver judges a
  // step by its own residual and turns this off.
  bool trueResidual = true;
  // Preparation kept from the last solve with the same matrix (fused PCG, matrix without dynamic entries); nullptr:
  // prepared afresh.
  PcgCache* cache = nullptr;
};

struct LinearSolveResult {
  int iterations = 0;             // PCG iterations (0 for the direct solve)
  double relativeResidual = 0.0;  // |Ax - b| / |b| of the returned x, computed in double (-1: trueResidual off)
  bool ok = false;                // false on a failed factorisation or non-finite result
};

// Solves A x = b for the SPD block matrix A (static + dynamic parts). x is overwritten (size of b); with
// options.warmStart its incoming value is the initial guess.
LinearSolveResult solveLinear(const BlockMatrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                              const LinearSolveOptions& options);

}  // namespace drape::newton
