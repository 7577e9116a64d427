// Block rows the Newton matrix couples as stiffly as it holds them (not in the paper; solver.cg.coupled_groups):
// the two ends of a zero-length stitch at 1e4 N/m, against a fabric of 10-1000 N/m and a mass term of about 1 N/m
// per vertex at a 10 ms step. Block-Jacobi inverts each vertex alone, so the mode where a stitched pair moves
// together keeps the stitch's stiffness in the preconditioned system and the PCG spends its iterations on it.
// Preconditioning such a group by the inverse of its whole (3m x 3m) submatrix removes that mode. The groups are
// found in the static part of the matrix: a block A_ij joins rows i and j when |tr A_ij| >= threshold
// sqrt(tr A_ii tr A_jj). The trace measures a coupling in all three directions: a stiff stitch (k I) couples a pair
// near 1 and the ends of a three-vertex chain near 1 / sqrt(2), a membrane edge (stiff along the edge only) its
// vertices below 0.6 on the meshes measured (docs/ENGINE.md). refresh() recomputes the groups' inverses, dynamic
// (contact) entries included.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "drape/newton/block_matrix.h"

namespace drape::newton {

class CoupledGroups {
 public:
  // The largest group: four panels' corners meeting at one seam point.
  static constexpr int kMaxSize = 4;

  CoupledGroups() = default;
  // Groups of 2..maxSize (at most kMaxSize) storage rows of a joined by static couplings at least `threshold`
  // (0 < threshold <= 1) of their diagonal blocks; a coupling that would make a group larger is left out. Then
  // refresh(a).
  CoupledGroups(const BlockMatrix& a, double threshold, int maxSize = kMaxSize);

  // The groups' inverses from a's current values (a has the pattern the groups were found in): the static blocks
  // between a group's rows and the dynamic entries between them. A group whose submatrix is not positive definite
  // takes the inverses of its diagonal blocks (block-Jacobi).
  void refresh(const BlockMatrix& a);

  bool empty() const { return count() == 0; }
  int count() const { return static_cast<int>(m_start.size()) - 1; }
  int rows() const { return static_cast<int>(m_rows.size()); }

  // z = (group submatrix)^-1 r on every group's rows (storage order, 3 per row), replacing block-Jacobi's values
  // there. Returns the change of r . z this makes.
  template <typename S>
  double apply(const Eigen::Matrix<S, Eigen::Dynamic, 1>& r, Eigen::Matrix<S, Eigen::Dynamic, 1>& z) const;

 private:
  std::vector<int> m_start{0};   // group g: m_rows[m_start[g], m_start[g + 1])
  std::vector<int> m_rows;       // storage rows, ascending within a group
  std::vector<int> m_groupOf;    // per storage row: its group, or -1
  std::vector<int> m_slot;       // per storage row: its place in its group
  std::vector<int> m_inverseAt;  // group g's inverse: column-major (3m)^2 values from m_inverse[m_inverseAt[g]]
  std::vector<double> m_inverse;
};

}  // namespace drape::newton
