#pragma once
// Domain-decomposed global solve (pd-dd section 4.2, eqs. 6-10): DOFs held by one domain are internal, by two
// duplicate (tied by a multiplier lambda), by more than two corner (one shared unknown x_C); the remainder
// R = internal + duplicate is factorised per domain. A solve computes x_C from the dense Schur system G_CC^*,
// then lambda from G_RR, then every domain's x_R in parallel (TBB). The result equals the monolithic solve of
// K x = b to round-off.
//
// Derived signs (with S_D^j carrying +1 for the lower-numbered domain of a duplicate, -1 for the other):
//   G_RR = sum_j S_D^j K_RR^-1 S_D^jT,  G_RC = sum_j S_D^j K_RR^-1 K_RC^j S_C^j,
//   G_CC = sum_j S_C^jT (K_CC^j - K_CR^j K_RR^-1 K_RC^j) S_C^j,
//   G_CC^* = G_CC + G_RC^T G_RR^-1 G_RC,  x_C = G_CC^*^-1 (b_C^* + G_RC^T G_RR^-1 b_R^*),
//   lambda = G_RR^-1 (b_R^* - G_RC x_C),  x_R^j = K_RR^-1 (b_R^j - K_RC^j S_C^j x_C - S_D^jT lambda).
// (The paper's eq. 10 prints the Schur term with the opposite sign convention.)
#include <cstdint>
#include <memory>
#include <vector>

#include "drape/pd/domain_partition.h"
#include "drape/pd/global_solver.h"

namespace drape::pd {

enum class DofClass : std::uint8_t { Internal, Duplicate, Corner };

class DomainDecomposedSolver final : public GlobalSolver {
 public:
  // domains: per-domain matrices whose sum is K (splitSystem); dofCount: size of K. extraCornerStride > 0 turns
  // every n-th duplicate DOF (in index order) into a corner as well (section 4.3). Factorises everything.
  DomainDecomposedSolver(const std::vector<DomainMatrix>& domains, int dofCount, int extraCornerStride = 0);
  ~DomainDecomposedSolver() override;

  void solve(const Eigen::MatrixX3d& b, Eigen::MatrixX3d& x) const override;
  int size() const override { return m_size; }
  bool ok() const override { return m_ok; }

  int domainCount() const;                 // domains with at least one DOF
  int cornerCount() const;                 // N_C
  int duplicateCount() const;              // N_B - N_C (size of lambda)
  int maxRemainder() const;                // largest N_R^j
  const std::vector<DofClass>& dofClasses() const;  // per DOF

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
  int m_size = 0;
  bool m_ok = false;
};

}  // namespace drape::pd
