// Dissipation potentials on strain rates for stretch and bending (newton-drape-pizana 5.3, after
// Sanchez-Banderas and Otaduy 2018): D(v) = beta * 0.5 * eps_dot^T K eps_dot with eps_dot = J v, J the strain
// Jacobian and K the elastic stiffness of the element, beta in seconds (paper: beta_s 1e-2, beta_b 1e-1).
// J is lagged at the step's start positions x_n, so the step term E(x) = h D((x - x_n)/h)
// = (beta / 2h) d^T J^T K J d, d = x - x_n, is quadratic with a constant SPD Hessian per step.
#pragma once

#include <vector>

#include "drape/newton/hinge_bending.h"
#include "drape/newton/stencil_set.h"
#include "drape/newton/stvk_membrane.h"

namespace drape::newton {

// Common part of the lagged dissipations: the step's start positions and assembly switches (set in beginStep).
class LaggedDissipation : public Energy {
 protected:
  void beginLagged(const StepContext& ctx) {
    m_previous = ctx.previousPositions;
    m_options = ctx.assembly;
  }
  const Eigen::VectorXd* m_previous = nullptr;
  AssemblyOptions m_options;
};

// Stretch dissipation on the Green strain rate of the StVK membrane: per triangle
// E = 0.5 (J d)^T W (J d), J the 3 x 9 Green strain Jacobian at x_n, W = beta A diag(kWarp, kWeft, 2 kShear) / h.
// J is kept as the deformation gradient F_n at x_n (6 numbers, not 27): with dF = F(x) - F_n (F is linear in x),
// J d = (f0 . dF0, f1 . dF1, (f0 . dF1 + f1 . dF0) / 2), f = F_n's columns, so a pass that has F(x) at hand (the
// membrane's) needs neither J nor x_n.
class MembraneDissipation : public LaggedDissipation {
 public:
  MembraneDissipation(std::vector<MembraneElement> elements, double beta);
  std::string_view name() const override { return "stretch_damping"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  void addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const override;
  void addCouplings(std::vector<std::pair<int, int>>& pairs) const override { m_stencils.addCouplings(pairs); }

  // Element Hessian of triangle s for this step, J_n^T W J_n (constant within it; beginStep first). e: the
  // membrane's element of triangle s (the same rest data as this energy's; a folding membrane passes the copy it has
  // at hand, saving a second read, and writes this Hessian's blocks itself from startF and factor).
  Eigen::Matrix<double, 9, 9> stencilHessian(int s, const MembraneElement& e) const;
  // Element gradient of triangle s at x, or at its deformation gradient f (beginStep first; e as above).
  Eigen::Matrix<double, 9, 1> stencilGradient(int s, const Eigen::VectorXd& x) const;
  Eigen::Matrix<double, 9, 1> stencilGradient(int s, const MembraneElement& e,
                                              const Eigen::Matrix<double, 3, 2>& f) const;
  // Set by the solver when the membrane on the same triangles folds this energy into its passes
  // (AssemblyOptions::foldDissipation): addGradient, addHessian and addGradientAndHessian then add nothing.
  void setFolded(bool folded) { m_folded = folded; }
  // The membrane on the same triangles, whose recorded deformation gradients beginStep takes over as F_n when
  // they were taken at x_n (nullptr: always computed).
  void setStartSource(const StvkMembrane* membrane) { m_source = membrane; }
  // F_n of triangle s and W / (A diag(kWarp, kWeft, 2 kShear)) = beta / h (times the ramp), for this step.
  const Eigen::Matrix<double, 3, 2>& startF(int s) const { return m_startF[s]; }
  double factor() const { return m_factor; }

 private:
  bool folded() const { return m_folded && m_options.foldDissipation; }
  // Hessian into h and, when g is given, the gradient into *g (one pass).
  void assemble(const Eigen::VectorXd& x, Eigen::VectorXd* g, BlockMatrix& h) const;
  // Strain rate times h, J d, of triangle s at deformation gradient f.
  Eigen::Vector3d strainChange(int s, const Eigen::Matrix<double, 3, 2>& f) const;
  // Diagonal of W for element e.
  Eigen::Vector3d weights(const MembraneElement& e) const { return m_factor * voigtStiffness(e); }
  // A (kWarp, kWeft, 2 kShear) of element e, N m.
  static Eigen::Vector3d voigtStiffness(const MembraneElement& e) {
    return e.area * Eigen::Vector3d(e.kWarp, e.kWeft, 2.0 * e.kShear);
  }

  std::vector<MembraneElement> m_elements;
  bool m_folded = false;
  double m_beta;
  StencilSet<3> m_stencils;
  const StvkMembrane* m_source = nullptr;
  std::vector<Eigen::Matrix<double, 3, 2>> m_startF;  // F_n per triangle, at x_n
  double m_factor = 0.0;                              // W / that = beta / h (times the stiffness ramp)
};

// Bending dissipation on the dihedral angle rate of the hinges: per hinge E = 0.5 c (g . d)^2 with g the gradient
// of the bending measure phi (the angle, faded on collapsing wings; hinge_bending.h) at x_n and c = beta k_e / h.
// g sums to zero over the hinge's four vertices (translation invariance; made exact by zeroSumOffset), so
// g . d = sum_k>0 g_k . (x_k - x_0) - o with the offset o the same sum at x_n: a pass reads no x_n. g and o are
// taken over (swapped, not copied) from the hinge bending's last gradient evaluation when that was at x_n (the
// accepted state of the last step): beginStep then makes no pass at all.
class BendingDissipation : public LaggedDissipation {
 public:
  BendingDissipation(std::vector<Hinge> hinges, double beta);
  std::string_view name() const override { return "bending_damping"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  void addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const override;
  void addCouplings(std::vector<std::pair<int, int>>& pairs) const override { m_stencils.addCouplings(pairs); }

  // Element Hessian of hinge s for this step and, when ge is given, the element gradient at the hinge's gathered
  // coordinates q (gatherHinge; beginStep first). stiffness: k_e of hinge s (a folding bending passes the copy it
  // has at hand, the same number as this energy's).
  Eigen::Matrix<double, 12, 12> stencilDerivatives(int s, const HingeCoords& q, double stiffness,
                                                   Eigen::Matrix<double, 12, 1>* ge) const;
  // Element gradient of hinge s at x, or at its gathered coordinates q (beginStep first; stiffness as above).
  Eigen::Matrix<double, 12, 1> stencilGradient(int s, const Eigen::VectorXd& x) const;
  Eigen::Matrix<double, 12, 1> stencilGradient(int s, const HingeCoords& q, double stiffness) const;
  // As MembraneDissipation::setFolded, for the hinge bending on the same hinges.
  void setFolded(bool folded) { m_folded = folded; }
  // The hinge bending on the same hinges, whose recorded gradients beginStep reuses (nullptr: always computed).
  void setGradientSource(const HingeBending* bending) { m_source = bending; }
  // This step's g and o of hinge s, and c / k_e = beta / h (times the ramp).
  const Eigen::Matrix<double, 12, 1>& startGradient(int s) const { return m_gradients[s]; }
  const double& startOffset(int s) const { return m_offsets[s]; }
  double factor() const { return m_factor; }

 private:
  bool folded() const { return m_folded && m_options.foldDissipation; }
  void assemble(const Eigen::VectorXd& x, Eigen::VectorXd* g, BlockMatrix& h) const;  // as MembraneDissipation's
  // g . (x - x_n) of hinge s (radians), from its gathered coordinates q at x.
  double angleChange(int s, const HingeCoords& q) const;

  std::vector<Hinge> m_hinges;
  bool m_folded = false;
  double m_beta;
  const HingeBending* m_source = nullptr;
  StencilSet<4> m_stencils;
  std::vector<Eigen::Matrix<double, 12, 1>> m_gradients;  // bending-measure gradient per hinge, at x_n
  std::vector<double> m_offsets;                          // o per hinge, radians
  double m_factor = 0.0;                                  // c / k_e = beta / h (times the stiffness ramp)
};

}  // namespace drape::newton
