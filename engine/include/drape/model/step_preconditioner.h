#pragma once
// The initial Hessian of the quasi-Newton step (quasi_newton.h): an SPD approximation H0 of the incremental
// potential's Hessian that is cheap to apply, such as the Projective Dynamics system M / h^2 + L (pd_preconditioner.h;
// Liu, Bouaziz and Kavan 2017, section 4). The solver hands it the step's h, the relaxation's stiffness scale and the
// stiffness of the terms that change within a run (contact, friction, a dragged vertex) per vertex.
#include <Eigen/Core>

namespace drape::model {

class StepPreconditioner {
 public:
  virtual ~StepPreconditioner() = default;
  // Prepares H0 ~ M / h^2 + scale x (stretch, shear, bending) + stitches and pins + diag(vertexStiffness) for one
  // step. vertexStiffness: |V|, N/m, the largest eigenvalue of each vertex's diagonal Hessian block of the changing
  // terms (0 where none). Returns false when H0 cannot be factorised.
  virtual bool prepare(double h, double scale, const Eigen::VectorXd& vertexStiffness) = 0;
  // Within a step: H0 takes on the changing terms' stiffness at a later iterate only where it grew much (a vertex
  // pushed into the body), so that small changes cost no update. Returns false when H0 cannot be factorised.
  virtual bool stiffen(const Eigen::VectorXd& vertexStiffness) = 0;
  // d = H0^-1 r (both 3|V|, flat x0, y0, z0, x1, ...).
  virtual void apply(const Eigen::VectorXd& r, Eigen::VectorXd& d) = 0;
  // Numeric factorisations of H0 so far (for statistics).
  virtual int factorisations() const = 0;
};

}  // namespace drape::model
