// Zero-length springs: stitches between vertex pairs or from a vertex to a point of an edge (the garment sews
// itself closed) and pins to fixed targets.
// Pins are stiff springs rather than removed DOFs, so every vertex stays a degree of freedom.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "drape/model/cloth_model.h"
#include "drape/newton/energy.h"

namespace drape::newton {

// E = sum 0.5 k |c_s(x)|^2 over stitches s; k in N/m. A vertex stitch (i, j) has c = x_i - x_j; an edge stitch
// (v on edge (a, b) at t, pd-dd section 4.4) has c = x_v - (1 - t) x_a - t x_b, a 3-vertex stencil coupling v, a
// and b. Both are zero-length springs of the same stiffness.
class StitchSprings : public Energy {
 public:
  StitchSprings(std::vector<std::pair<int, int>> pairs, double stiffness, const std::vector<model::EdgeStitch>& edges = {});
  std::string_view name() const override { return "stitches"; }
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  void addCouplings(std::vector<std::pair<int, int>>& pairs) const override;
  // Largest |c_s(x)| (distance between a stitched vertex and its partner or its edge point), metres.
  double maxGap(const Eigen::VectorXd& x) const;

 private:
  // c = sum_k w[k] x_{vertices[k]} over the first size entries.
  struct Stencil {
    std::array<int, 3> vertices{};
    std::array<double, 3> w{};
    int size = 0;
  };
  Eigen::Vector3d constraint(const Stencil& s, const Eigen::VectorXd& x) const;

  std::vector<Stencil> m_stencils;
  double m_stiffness;
};

// E = sum 0.5 k |x_i - p_i|^2 over pinned vertices with targets p_i (metres); k in N/m.
// With a trajectory, every step moves the targets to where the pins are at the end of the step.
class PinSprings : public Energy {
 public:
  using Trajectory = std::function<Eigen::Vector3d(int k, double t)>;
  // trajectory(k, t): target of vertices[k] at scene time t; timeOffset: scene time at the solver's time 0, s.
  PinSprings(std::vector<int> vertices, std::vector<Eigen::Vector3d> targets, double stiffness,
             Trajectory trajectory = {}, double timeOffset = 0.0, std::string name = "pins");
  std::string_view name() const override { return m_name; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  void setTarget(int k, const Eigen::Vector3d& p) { m_targets[k] = p; }
  // Replaces the pinned set (a dragged vertex: one spring to the cursor; none when released).
  void setPins(std::vector<int> vertices, std::vector<Eigen::Vector3d> targets);
  const std::vector<Eigen::Vector3d>& targets() const { return m_targets; }

 private:
  std::vector<int> m_vertices;
  std::vector<Eigen::Vector3d> m_targets;
  double m_stiffness;
  Trajectory m_trajectory;
  double m_timeOffset;
  std::string m_name;
};

}  // namespace drape::newton
