#pragma once
// Untangling: where the cloth already passes through itself, a pull that shortens the intersection contour, the
// closed curve along which the crossing triangles cut each other (the contour minimisation of Volino and
// Magnenat-Thalmann 2006). The energy is
//   E(x) = f * sum over crossing triangle pairs (t, u) of |P_tu(x) - Q_tu(x)|,
// the length of the segment along which t and u cross, times a force f (newtons): the contour shrinks, and the
// crossing with it, as a loop of string under tension f would. A contour length has no useful curvature, so the term
// adds its gradient and no Hessian: the step sees it as a force.
// The crossings come from the self-contact term (self_contact.h), found at the start of each step. How the pull
// enters a step is the solver's choice (ContourPull): followed through the step, or held at its start.
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "drape/newton/contact/self_contact.h"
#include "drape/newton/energy.h"

namespace drape::newton {

// Length of the segment along which triangles (a0, a1, a2) and (b0, b1, b2) cross, 0 when they do not cross (or
// only touch). gradient (optional): d length / d (a0, a1, a2, b0, b1, b2).
double crossingLength(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                      const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2,
                      Eigen::Matrix<double, 18, 1>* gradient = nullptr);

// How the contour's pull enters a step.
enum class ContourPull {
  // The exact contour at every evaluation: every pair of triangles near the step's crossings (a few rings around) is
  // evaluated, so that a contour that moves on during the step is still followed, and the pull stops where a crossing
  // clears. It switches on and off within the step, which a quasi-Newton step (the preview) takes in its stride.
  Followed,
  // The pull of the crossings at the step's start, held for the whole step: the linear potential
  // f * gradient(length)(x_n) . (x - x_n). A Newton step's equations stay smooth (a pull that switches on and off
  // inside the step stalls Newton's iterations and splits its steps while the seams close); the next step pulls
  // again where crossings remain.
  HeldOverTheStep,
};

class IntersectionContourEnergy : public Energy {
 public:
  // self: the cloth's self contact, which finds the crossings at the start of each step (beginStep after its own).
  // force: the contour's tension, newtons.
  IntersectionContourEnergy(const SelfContactEnergy* self, double force, ContourPull pull);

  std::string_view name() const override { return "intersection_contour"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override {
    (void)x;
    (void)h;
  }

  // Triangle pairs followed during this step (none while the cloth crosses nowhere; none when the pull is held).
  int candidateCount() const { return static_cast<int>(m_candidates.size()); }

 private:
  void followAround(const std::vector<std::pair<int, int>>& crossings, const Eigen::VectorXd& x);
  void holdAt(const std::vector<std::pair<int, int>>& crossings, const Eigen::VectorXd& x);

  const SelfContactEnergy* m_self;
  double m_force;
  ContourPull m_pull;
  std::vector<std::pair<int, int>> m_candidates;  // Followed
  Eigen::VectorXd m_heldAt, m_heldGradient;       // HeldOverTheStep: x_n and the pull's gradient there (empty: none)
};

}  // namespace drape::newton
