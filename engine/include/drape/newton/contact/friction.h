#pragma once
// Lagged Coulomb friction as a smooth dissipative potential (IPC, Li et al. 2020, section 5; used with the
// penalty contacts of newton-drape-pizana 3.2). At the start of each step the active contacts of the contact
// energies are taken at x_n with their normal force lambda = k (thickness - d), normal n and stencil weights w;
// these stay fixed for the step. With the tangential relative displacement u = (I - n n^T) sum_i w_i (x_i - x_n,i)
//   D(x) = sum_c mu lambda_c f0(|u_c|),  f0' = f1,  f1(y) = 2y/eps - y^2/eps^2 (y < eps), 1 otherwise,
// eps = epsV * h: static friction below a slip of epsV * h, kinetic (force mu lambda) above. D is C1 and its
// Hessian sum_c mu lambda_c w_i w_j [f1(y)/y I + (f1'(y) y - f1(y))/y^3 u u^T] restricted to the tangent plane
// is positive semi-definite for every y (no projection needed).
// Along u that Hessian is mu lambda f1'(y), zero in the sliding regime. At a step's first Newton iterate the slip is
// predicted from the vertex's velocity (u = h v_n); where the contact should stick, the linear model then sees a
// constant force and the step overshoots, turning the slip round, and the residual error 2 mu lambda h is far
// below tau_n: the next step overshoots back, and the contact chatters every step without ever sticking (0.04 m/s
// on the default scene; the PCG warm start then fails, docs/BENCHMARKS.md). There (addPredictionGradientAndHessian)
// the energy adds the isotropic majorizer mu lambda f1(y)/y (I - n n^T) instead: f0 is concave in y^2, so the
// quadratic with this curvature lies above D and touches it at u (the half-quadratic bound): its step shrinks a
// slip towards the sticking point but cannot pass it. Later iterations take the Hessian.
#include <Eigen/Core>
#include <vector>

#include "drape/collision/contact_stencil.h"
#include "drape/newton/contact/avatar_contact.h"
#include "drape/newton/contact/avatar_feature_contact.h"
#include "drape/newton/contact/self_contact.h"
#include "drape/newton/energy.h"

namespace drape::newton {

struct FrictionParameters {
  double mu = 0.3;                   // Coulomb coefficient (> 0; a coefficient of 0 creates no friction energy at all)
  double epsV = 1e-3;                // slip velocity below which friction acts as a stiff static spring, m/s
  bool majorizeAtPrediction = true;  // the majorizer at a step's first iterate (contact.friction_majorizer)
};

// Smoothed friction magnitude profile f1 and its primitive f0 (f0(0) = eps / 3, f0(y) = y for y >= eps).
double frictionF0(double y, double eps);
double frictionF1(double y, double eps);

class FrictionEnergy : public Energy {
 public:
  // Any source may be null; they must outlive this energy (the factory keeps them in the same list).
  FrictionEnergy(const AvatarContactEnergy* avatar, const SelfContactEnergy* self, FrictionParameters params,
                 const AvatarFeatureContactEnergy* features = nullptr);

  std::string_view name() const override { return "friction"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  // The gradient and, with majorizeAtPrediction, the isotropic majorizer (above) instead of the Hessian.
  void addPredictionGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const override;

  // Lagged contacts of the current step and their normal forces (N).
  struct LaggedContact {
    collision::ContactStencil stencil;
    double normalForce = 0.0;
    Eigen::Matrix3d tangent = Eigen::Matrix3d::Zero();  // I - n n^T
  };
  const std::vector<LaggedContact>& laggedContacts() const { return m_contacts; }
  // Sets the lagged contacts directly (tests; custom contact sources). start: x_n; h: time step, s.
  void setLagged(std::vector<LaggedContact> contacts, const Eigen::VectorXd& start, double h);

 private:
  Eigen::Vector3d slip(const LaggedContact& c, const Eigen::VectorXd& x) const;
  void addBlocks(const Eigen::VectorXd& x, BlockMatrix& h, bool majorizer) const;

  const AvatarContactEnergy* m_avatar = nullptr;
  const SelfContactEnergy* m_self = nullptr;
  const AvatarFeatureContactEnergy* m_features = nullptr;
  FrictionParameters m_params;
  double m_eps = 1e-6;  // epsV * h, metres
  Eigen::VectorXd m_start;
  std::vector<LaggedContact> m_contacts;
};

}  // namespace drape::newton
