// Discrete hinge bending (newton-drape-pizana 3.2; Bridson et al. 2003, Grinspun et al. 2003 "discrete shells").
// For each interior edge e = (x0, x1) with opposite vertices x2 (triangle x0 x1 x2) and x3 (triangle x1 x0 x3),
// theta is the signed dihedral angle atan2((nA x nB) . e/|e|, nA . nB) with nA = (x1-x0)x(x2-x0),
// nB = (x3-x0)x(x1-x0); rest angle 0 (flat). Energy E_e = 0.5 * k_e * theta^2 with
// k_e = kb * 3 |e_rest|^2 / (A_A + A_B) (discrete-shells scaling, rest lengths and areas), kb in N m from
// the fabric: kb = bendWarp * d_y^2 + bendWeft * d_x^2 for the rest edge direction d (fold line along d).
#pragma once

#include <array>
#include <vector>

#include "drape/newton/cloth_model.h"
#include "drape/newton/energy.h"
#include "drape/newton/stencil_set.h"

namespace drape::newton {

struct Hinge {
  std::array<int, 4> v{};  // x0, x1 (edge), x2, x3 (opposite vertices)
  double stiffness = 0.0;  // k_e, N m
};

// Interior edges shared by exactly two triangles of the model, with their stiffness (0-stiffness ones dropped).
std::vector<Hinge> buildHinges(const ClothModel& model);

// Signed dihedral angle of a hinge (radians) and its gradient w.r.t. the 12 coordinates (closed form).
double hingeAngle(const Hinge& hinge, const Eigen::VectorXd& x);
Eigen::Matrix<double, 12, 1> hingeAngleGradient(const Hinge& hinge, const Eigen::VectorXd& x);
// The same gradient by forward-mode automatic differentiation (reference for tests and the switched-off path).
Eigen::Matrix<double, 12, 1> hingeAngleGradientAutodiff(const Hinge& hinge, const Eigen::VectorXd& x);
// Gradient in closed form or by automatic differentiation; theta receives the angle (radians).
Eigen::Matrix<double, 12, 1> hingeAngleGradient(const Hinge& hinge, const Eigen::VectorXd& x, bool closedForm,
                                                double& theta);
// Exact Hessian of the angle (12 x 12), by forward-mode automatic differentiation of the gradient.
Eigen::Matrix<double, 12, 12> hingeAngleHessian(const Hinge& hinge, const Eigen::VectorXd& x);

class BendingDissipation;

class HingeBending : public Energy {
 public:
  explicit HingeBending(const ClothModel& model);
  std::string_view name() const override { return "bending"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  // Default: Gauss-Newton k_e grad(theta) grad(theta)^T (SPD); exact adds k_e theta Hess(theta).
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  void addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const override;
  void addCouplings(std::vector<std::pair<int, int>>& pairs) const override;

  void setExactHessian(bool exact) { m_exactHessian = exact; }
  const std::vector<Hinge>& hinges() const { return m_hinges; }
  bool empty() const { return m_hinges.empty(); }
  // The bending dissipation on the same hinges (same order), folded into this energy's Hessian passes when
  // AssemblyOptions::foldDissipation is on (the solver also calls its setFolded). nullptr: none.
  void foldDissipation(const BendingDissipation* dissipation) { m_dissipation = dissipation; }

 private:
  const BendingDissipation* m_dissipation = nullptr;
  // Hessian into h and, when g is given, the gradient into *g (one pass).
  void assemble(const Eigen::VectorXd& x, Eigen::VectorXd* g, BlockMatrix& h) const;

  std::vector<Hinge> m_hinges;
  StencilSet<4> m_stencils;  // hinges, coloured, with their block slots
  double m_scale = 1.0;
  bool m_exactHessian = false;
  AssemblyOptions m_options;
};

}  // namespace drape::newton
