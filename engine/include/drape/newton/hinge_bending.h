// Discrete hinge bending (newton-drape-pizana 3.2; Bridson et al. 2003, Grinspun et al. 2003 "discrete shells").
// For each interior edge e = (x0, x1) with opposite vertices x2 (triangle x0 x1 x2) and x3 (triangle x1 x0 x3),
// theta is the signed dihedral angle atan2((nA x nB) . e/|e|, nA . nB) with nA = (x1-x0)x(x2-x0),
// nB = (x3-x0)x(x1-x0); rest angle 0 (flat). Energy E_e = 0.5 * k_e * phi^2 with
// k_e = kb * 3 |e_rest|^2 / (A_A + A_B) (discrete-shells scaling, rest lengths and areas), kb in N m from
// the fabric: kb = bendWarp * d_y^2 + bendWeft * d_x^2 for the rest edge direction d (fold line along d).
// phi = theta * c(J_A) * c(J_B) is the bending measure: J = |n| / |n_rest| is a wing's area ratio and
// c(J) = s^3 (10 - 15 s + 6 s^2), s = J / kHingeCollapseRatio, for J < kHingeCollapseRatio, else 1 (C2).
// phi = theta on every wing above that ratio; it fades out on a wing collapsing to zero area, where theta is
// undefined (it jumps by pi as the wing passes through the edge line) and |grad theta| = 1 / (wing height)
// grows without bound: with theta alone such a hinge made the Newton system arbitrarily stiff and no time step
// converged (issue 5). With the fade, E is C2 with a bounded Hessian everywhere; a collapsed triangle carries no
// bending (the membrane does not stop triangles collapsing: StVK resists compression less the more it grows).
#pragma once

#include <array>
#include <vector>

#include "drape/model/cloth_model.h"
#include "drape/newton/energy.h"
#include "drape/newton/recorded_gradient.h"
#include "drape/newton/stencil_set.h"

namespace drape::newton {

struct Hinge {
  std::array<int, 4> v{};  // x0, x1 (edge), x2, x3 (opposite vertices)
  double stiffness = 0.0;  // k_e, N m
  // |nA|, |nB| at rest (twice the rest areas of the wings x0 x1 x2 and x1 x0 x3), m^2; 0: no fade on that wing.
  std::array<double, 2> restNormalLength{};
};

// Area ratio below which a wing's bending fades out (see the top of this file). Well below the compression
// of cloth in a drape, so the bending measure is the dihedral angle in every sound state.
inline constexpr double kHingeCollapseRatio = 0.2;

// The 12 stacked coordinates (x0, x1, x2, x3) of a hinge.
using HingeCoords = Eigen::Matrix<double, 12, 1>;
HingeCoords gatherHinge(const Hinge& hinge, const Eigen::VectorXd& x);

// Interior edges shared by exactly two triangles of the model, with their stiffness (0-stiffness ones dropped).
std::vector<Hinge> buildHinges(const model::ClothModel& model);

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

// Bending measure phi (radians; theta faded on collapsing wings, see the top of this file) and its gradient;
// closedForm as hingeAngleGradient. Finite for every x, 0 with a zero-area wing.
Eigen::Matrix<double, 12, 1> hingeBendGradient(const Hinge& hinge, const Eigen::VectorXd& x, bool closedForm,
                                               double& phi);
// The same from the hinge's gathered coordinates q (gatherHinge).
Eigen::Matrix<double, 12, 1> hingeBendGradient(const Hinge& hinge, const HingeCoords& q, bool closedForm, double& phi);
double hingeBendMeasure(const Hinge& hinge, const Eigen::VectorXd& x);
// Exact Hessian of phi (12 x 12), by automatic differentiation (exact-Hessian mode and tests).
Eigen::Matrix<double, 12, 12> hingeBendHessian(const Hinge& hinge, const Eigen::VectorXd& x);
// Makes a hinge's gradient g (taken at x) sum to zero over its four vertices exactly, g_0 = -(g_1 + g_2 + g_3)
// (translation invariance), and returns sum_k>0 g_k . (x_k - x_0): then g . (y - x) is the same sum at y minus
// this one, with no x kept (the bending dissipation's linearised angle change).
double zeroSumOffset(const Hinge& hinge, const Eigen::VectorXd& x, Eigen::Matrix<double, 12, 1>& g);
// The same from the hinge's gathered coordinates q at x.
double zeroSumOffset(const HingeCoords& q, Eigen::Matrix<double, 12, 1>& g);

class BendingDissipation;

class HingeBending : public Energy {
 public:
  explicit HingeBending(const model::ClothModel& model);
  std::string_view name() const override { return "bending"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addGuessGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override { gradientPass(x, g, false); }
  // Default: Gauss-Newton k_e grad(phi) grad(phi)^T (SPD); exact adds k_e phi Hess(phi).
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  void addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const override;
  void addCouplings(std::vector<std::pair<int, int>>& pairs) const override;

  void setExactHessian(bool exact) { m_exactHessian = exact; }
  const std::vector<Hinge>& hinges() const { return m_hinges; }
  bool empty() const { return m_hinges.empty(); }
  // The bending dissipation on the same hinges (same order), folded into this energy's Hessian passes when
  // AssemblyOptions::foldDissipation is on (the solver also calls its setFolded). nullptr: none.
  void foldDissipation(const BendingDissipation* dissipation) { m_dissipation = dissipation; }
  // Gradient passes (addGradient) record grad(phi) of every hinge, made zero-sum with its offset (zeroSumOffset),
  // and the positions they were taken at, for the bending dissipation's next beginStep: the line search's last
  // evaluation is the next step's start x_n.
  void setRecordAngleGradients(bool record) { m_record = record; }
  bool addRecordedStepStartGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override {
    return m_recordedGradient.addTo(x, m_scale, g);
  }
  void setRecordStepStartGradient(bool record) override { m_recordedGradient.enabled = record; }
  // Whether the recorded gradients were taken at x (bit for bit) in the given form.
  bool hasRecordedGradientsAt(const Eigen::VectorXd& x, bool closedForm) const;
  // When they were: swaps them and their offsets into gradients and offsets (no copy; the record is then
  // empty) and returns true. Otherwise returns false and leaves both untouched.
  bool takeRecordedGradients(const Eigen::VectorXd& x, bool closedForm,
                             std::vector<Eigen::Matrix<double, 12, 1>>& gradients, std::vector<double>& offsets) const;

 private:
  const BendingDissipation* m_dissipation = nullptr;
  // Hessian into h and, when g is given, the gradient into *g (one pass).
  void assemble(const Eigen::VectorXd& x, Eigen::VectorXd* g, BlockMatrix& h) const;

  std::vector<Hinge> m_hinges;
  StencilSet<4> m_stencils;  // hinges, coloured, with their block slots
  double m_scale = 1.0;
  bool m_exactHessian = false;
  AssemblyOptions m_options;
  bool m_record = false;
  mutable std::vector<Eigen::Matrix<double, 12, 1>> m_recorded;  // zero-sum grad(phi) per hinge at m_recordedAt
  mutable std::vector<double> m_recordedOffsets;                  // zeroSumOffset per hinge
  mutable Eigen::VectorXd m_recordedAt;
  mutable bool m_recordedClosedForm = true;
  // addGradient (record: as set up) and addGuessGradient (record: false).
  void gradientPass(const Eigen::VectorXd& x, Eigen::VectorXd& g, bool record) const;
  // The closed-form part of gradientPass over the hinges ids[0 .. count): g += each hinge's gradient (with the
  // folded dissipation's when fold is given); recordAngles: into m_recorded; recordedGradient: the elastic share.
  void batchGradients(const Eigen::VectorXd& x, const int* ids, int count, bool recordAngles,
                      Eigen::VectorXd* recordedGradient, const BendingDissipation* fold, Eigen::VectorXd& g) const;
  mutable RecordedGradient m_recordedGradient;  // elastic gradient of the last addGradient pass (no dissipation)
};

}  // namespace drape::newton
