// Zero-length springs: stitches between vertex pairs (the garment sews itself closed) and pins to fixed targets.
// Pins are stiff springs rather than removed DOFs, so every vertex stays a degree of freedom.
#pragma once

#include <vector>

#include "drape/newton/energy.h"

namespace drape::newton {

// E = sum 0.5 k |x_i - x_j|^2 over stitched pairs; k in N/m.
class StitchSprings : public Energy {
 public:
  StitchSprings(std::vector<std::pair<int, int>> pairs, double stiffness);
  std::string_view name() const override { return "stitches"; }
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  void addCouplings(std::vector<std::pair<int, int>>& pairs) const override;
  // Largest distance between stitched vertices, metres.
  double maxGap(const Eigen::VectorXd& x) const;

 private:
  std::vector<std::pair<int, int>> m_pairs;
  double m_stiffness;
};

// E = sum 0.5 k |x_i - p_i|^2 over pinned vertices with targets p_i (metres); k in N/m.
class PinSprings : public Energy {
 public:
  PinSprings(std::vector<int> vertices, std::vector<Eigen::Vector3d> targets, double stiffness);
  std::string_view name() const override { return "pins"; }
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  void setTarget(int k, const Eigen::Vector3d& p) { m_targets[k] = p; }

 private:
  std::vector<int> m_vertices;
  std::vector<Eigen::Vector3d> m_targets;
  double m_stiffness;
};

}  // namespace drape::newton
