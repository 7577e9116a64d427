// Gravity and air drag (newton-drape-pizana eq. 5) on lumped vertex masses.
#pragma once

#include "drape/model/cloth_model.h"
#include "drape/newton/energy.h"

namespace drape::newton {

// Lumped masses, kg per vertex: a third of density * rest area of every incident triangle. Size |V|.
Eigen::VectorXd lumpedVertexMasses(const model::ClothModel& model);

// E = -sum m_i g . x_i (joules).
class Gravity : public Energy {
 public:
  Gravity(Eigen::VectorXd masses, const Eigen::Vector3d& g);
  std::string_view name() const override { return "gravity"; }
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd&, BlockMatrix&) const override {}

 private:
  Eigen::VectorXd m_force;  // 3|V|, newtons: m_i g
};

// Air drag F = -alpha m v as the dissipation potential D(v) = 0.5 alpha m |v|^2 in the step's incremental
// potential: E(x) = h D((x - x_n) / h) = alpha m |x - x_n|^2 / (2h). alpha in 1/s.
class AirDrag : public Energy {
 public:
  AirDrag(Eigen::VectorXd masses, double alpha);
  std::string_view name() const override { return "air_drag"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;

 private:
  Eigen::VectorXd m_masses;
  double m_alpha;
  double m_h = 1e-3;
  const Eigen::VectorXd* m_previous = nullptr;
};

}  // namespace drape::newton
