// Anisotropic Saint Venant-Kirchhoff membrane in the pattern's material frame (newton-drape-pizana 3.2).
// Per triangle with rest coordinates u_k (2D, metres) and positions x_k (3D): F = [x1-x0, x2-x0] Dm^-1 (3x2),
// Green strain E = (F^T F - I) / 2, energy = A * 0.5 * (kWarp E00^2 + kWeft E11^2 + 2 kShear E01^2)
// with A the rest area (m^2) and stiffness in N/m. No Poisson coupling between warp and weft.
#pragma once

#include <array>
#include <vector>

#include "drape/model/cloth_model.h"
#include "drape/newton/energy.h"
#include "drape/newton/recorded_gradient.h"
#include "drape/newton/stencil_set.h"

namespace drape::newton {

class MembraneDissipation;

// Precomputed rest data of one triangle.
struct MembraneElement {
  std::array<int, 3> v{};                 // vertex indices
  std::array<Eigen::Vector2d, 3> c;       // dF/dx_k = c_k^T: F = sum_k x_k c_k^T
  double area = 0.0;                      // rest area, m^2
  double kWarp = 0.0, kWeft = 0.0, kShear = 0.0;  // N/m
};

// Rest data for every triangle. Throws std::invalid_argument on a degenerate rest triangle.
std::vector<MembraneElement> buildMembraneElements(const model::ClothModel& model);

// Deformation gradient F (3 x 2: the rest frame's warp and weft directions mapped to 3D) of element e at x.
Eigen::Matrix<double, 3, 2> deformationGradient(const MembraneElement& e, const Eigen::VectorXd& x);

// Green strain rows (Voigt E00, E11, E01) differentiated w.r.t. the 9 triangle coordinates: 3 x 9, at x or at
// the deformation gradient f.
Eigen::Matrix<double, 3, 9> greenStrainJacobian(const MembraneElement& e, const Eigen::VectorXd& x);
Eigen::Matrix<double, 3, 9> greenStrainJacobian(const MembraneElement& e, const Eigen::Matrix<double, 3, 2>& f);

class StvkMembrane : public Energy {
 public:
  explicit StvkMembrane(const model::ClothModel& model);
  std::string_view name() const override { return "membrane"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addGuessGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override { gradientPass(x, g, false); }
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  void addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const override;
  void addCouplings(std::vector<std::pair<int, int>>& pairs) const override;
  bool addRecordedStepStartGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override {
    return m_recorded.addTo(x, m_scale, g);
  }
  void setRecordStepStartGradient(bool record) override { m_recorded.enabled = record; }

  // Exact Hessian (for tests) instead of the default projected one: material term J^T C J plus the geometric
  // term with the stress S clamped to its positive part, which is SPD.
  void setExactHessian(bool exact) { m_exactHessian = exact; }
  // 9x9 Hessian of one element (exact or projected per the flag above).
  Eigen::Matrix<double, 9, 9> elementHessian(const MembraneElement& e, const Eigen::VectorXd& x) const;
  // The element Hessian and (into ge) the element gradient, sharing F and the strain Jacobian.
  Eigen::Matrix<double, 9, 9> elementDerivatives(const MembraneElement& e, const Eigen::VectorXd& x,
                                                 Eigen::Matrix<double, 9, 1>* ge) const;
  // The same at the element's deformation gradient f.
  Eigen::Matrix<double, 9, 9> elementDerivatives(const MembraneElement& e, const Eigen::Matrix<double, 3, 2>& f,
                                                 Eigen::Matrix<double, 9, 1>* ge) const;
  const std::vector<MembraneElement>& elements() const { return m_elements; }
  // The stretch dissipation on the same triangles (same order), folded into this energy's Hessian passes when
  // AssemblyOptions::foldDissipation is on (the solver also calls its setFolded). nullptr: none.
  void foldDissipation(const MembraneDissipation* dissipation) { m_dissipation = dissipation; }
  // Gradient passes (addGradient) record every triangle's deformation gradient and the positions they were taken
  // at, for the stretch dissipation's next beginStep (its F_n), as HingeBending::setRecordAngleGradients.
  void setRecordDeformationGradients(bool record) { m_recordF = record; }
  // When the recorded deformation gradients were taken at x (bit for bit): swaps them into f (no copy; the
  // record is then empty) and returns true. Otherwise returns false and leaves f untouched.
  bool takeRecordedDeformationGradients(const Eigen::VectorXd& x, std::vector<Eigen::Matrix<double, 3, 2>>& f) const;

 private:
  const MembraneDissipation* m_dissipation = nullptr;
  std::vector<MembraneElement> m_elements;
  StencilSet<3> m_stencils;  // triangles, coloured, with their block slots
  double m_scale = 1.0;
  bool m_exactHessian = false;
  AssemblyOptions m_options;
  // Hessian into h and, when g is given, the gradient into *g (one pass).
  void assemble(const Eigen::VectorXd& x, Eigen::VectorXd* g, BlockMatrix& h) const;
  // addGradient (record: as set up) and addGuessGradient (record: false).
  void gradientPass(const Eigen::VectorXd& x, Eigen::VectorXd& g, bool record) const;
  // gradientPass over the triangles ids[0 .. count) with AssemblyOptions::batchedGradients: g += each triangle's
  // gradient (with the folded dissipation's when fold is given); recordF: F into m_recordedF; recordedGradient: the
  // elastic share.
  void batchGradients(const Eigen::VectorXd& x, const int* ids, int count, bool recordF,
                      Eigen::VectorXd* recordedGradient, const MembraneDissipation* fold, Eigen::VectorXd& g) const;
  mutable RecordedGradient m_recorded;  // elastic gradient of the last addGradient pass (without the dissipation)
  bool m_recordF = false;
  mutable std::vector<Eigen::Matrix<double, 3, 2>> m_recordedF;  // F per triangle at m_recordedFAt
  mutable Eigen::VectorXd m_recordedFAt;
};

}  // namespace drape::newton
