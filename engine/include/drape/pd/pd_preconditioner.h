#pragma once
// The quasi-Newton preview's initial Hessian (newton/step_preconditioner.h): the Projective Dynamics system of the
// drape's cloth model, K = (1 / h^2 + alpha / h) M + scale (1 + beta_s / h) (stretch, shear) + scale (1 + beta_b / h)
// bending + stitches (pd_system.h; the drape's air drag alpha and strain-rate dissipations beta_s, beta_b add
// their Hessians, alpha M / h and beta / h times the stiffness, to the same pattern), one scalar matrix
// for the three coordinates, solved by the domain-decomposed solve (dd_solver.h) on METIS domains, or, once the
// changing terms (contact, friction, a dragged vertex) add stiffness on some vertices, by the Cholesky factor of
// K + diag(that stiffness) updated by rank-k updates as it changes (contact_factor.h). Pinned vertices (springs in
// the drape) are eliminated from K; their direction is r / (m / h^2 + pin stiffness + their changing stiffness).
// K is factorised again only when h or the stiffness scale differ by more than a factor of two from the ones it was
// factorised for: it is a preconditioner, and a K of a nearby h preconditions as well.
#include <memory>
#include <vector>

#include "drape/model/cloth_model.h"
#include "drape/model/step_preconditioner.h"
#include "drape/pd/preview_settings.h"

namespace drape::pd {

class PdPreconditioner final : public model::StepPreconditioner {
 public:
  // stitchStiffness, pinStiffness: the drape's (N/m); alpha (1/s), betaStretch, betaBend (s): its air drag and
  // dissipations (newton_solver.h). domains: METIS domains of the decomposed solve (0 = the number
  // of threads); kind: decomposed or monolithic. Partitions once; factorises on the first prepare.
  PdPreconditioner(const model::ClothModel& model, double stitchStiffness, double pinStiffness, double alpha,
                   double betaStretch, double betaBend, int domains = 0,
                   GlobalSolverKind kind = GlobalSolverKind::DomainDecomposed);
  ~PdPreconditioner() override;

  bool prepare(double h, double scale, const Eigen::VectorXd& vertexStiffness) override;
  bool stiffen(const Eigen::VectorXd& vertexStiffness) override;
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& d) override;
  int factorisations() const override;

  int domainCount() const;
  const std::vector<int>& triangleDomain() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace drape::pd
