#pragma once
// The fast preview: domain-decomposed Projective Dynamics (pd-dd-lu2025). Built from the same ClothModel as the
// Newton drape solver so a Simulation can run the preview and hand its positions to the drape.
//   step(): z = x + h v + h^2 g; L-G iterations (local: Gauss-Seidel or Jacobi; global: K x = b by the
//   domain-decomposed or monolithic CHOLMOD solve, then the collision-aware correction when contacts exist)
//   until the largest vertex move of an iteration, divided by the largest extent of the cloth's box, falls
//   below settings.tolerance, or settings.maxIterations is reached.
#include <Eigen/Core>
#include <atomic>
#include <memory>
#include <vector>

#include "drape/model/cloth_model.h"
#include "drape/pd/preview_settings.h"

namespace drape::collision {
class AvatarCollider;
}

namespace drape::pd {

enum class PreviewStatus { Converged, MaxIterations, Diverged, Cancelled };
const char* toString(PreviewStatus status);

struct PreviewReport {
  PreviewStatus status = PreviewStatus::Converged;
  int iterations = 0;          // L-G iterations
  double residual = 0.0;       // normalised move of the last iteration (compared with the tolerance)
  int contacts = 0;            // contact constraints active in the last iteration (one per DOF, merged)
  int ccdContacts = 0;         // of the last iteration's avatar contacts, those found by CCD
  int staticFriction = 0;      // of the last iteration's avatar contacts, those held by static friction
  int selfContacts = 0;        // cloth-cloth vertex-triangle constraints of the last iteration (before merging)
  int selfResolved = 0;        // cloth-cloth pairs closer than the thickness (or crossed) projected at step end
  int selfCrossed = 0;         // cloth-cloth pairs still crossed after that projection (0 = none left)
  int avatarResolved = 0;      // vertices moved out of the avatar at step end (AvatarContacts::resolve)
  int sdIterations = 0;        // summed over the step
  int pcgIterations = 0;       // summed over the step
  double collisionTime = 0.0;  // seconds: contact detection + collision-aware correction
  double contactSolveTime = 0.0;  // seconds: of collisionTime, the collision-aware correction (SD + PCG)
  int contactChurn = 0;        // contact DOFs that joined or left the set between consecutive L-G iterations
  double contactResidual = 0.0;  // relative residual of eq. 14 left by the last collision-aware solve
  double localTime = 0.0;      // seconds
  double globalTime = 0.0;     // seconds: collision-free solves
  double wallTime = 0.0;       // seconds, whole step
  int domains = 0;             // domains used by the global solve and the local step
  double timeStep = 0.0;       // seconds: h of the step taken (settings.timeStep / 2^k, see step())
  int splits = 0;              // attempts redone at half the time step because the L-G loop hit its cap
  bool sewn = false;           // the garment counted as sewn during this step (settings.sewnGap)
};

class PreviewSolver {
 public:
  // Validates the model (throws InputError naming the element), partitions, and prefactorises. collider: optional
  // avatar, shared with other solvers; null = no avatar contact.
  PreviewSolver(const model::ClothModel& model, const PreviewSettings& settings,
                std::shared_ptr<const collision::AvatarCollider> collider = nullptr);
  ~PreviewSolver();
  PreviewSolver(const PreviewSolver&) = delete;
  PreviewSolver& operator=(const PreviewSolver&) = delete;

  // One time step of h = settings.timeStep / 2^k. An attempt whose L-G loop hits settings.maxIterations is redone
  // from the step's start at h / 2, down to settings.timeStep / 2^settings.maxHalvings (where a capped step is
  // kept); after settings.growAfterSteps converged steps h doubles back. The system of each h is factorised on
  // first use and kept. Iterations and times in the report count every attempt. Never throws for numerical
  // trouble: non-finite positions restore the state before the step and report Diverged; a cancel request restores
  // it and reports Cancelled.
  PreviewReport step();
  // Thread-safe; checked between L-G iterations.
  void requestCancel();
  void clearCancel();
  // Pulls vertex towards target (metres) with settings.dragWeight from the next step on (a grabbed vertex);
  // vertex < 0 releases it. A pinned vertex cannot be dragged (ignored).
  void setDrag(int vertex, const Eigen::Vector3d& target);

  const Eigen::VectorXd& positions() const;   // 3|V|, metres
  const Eigen::VectorXd& velocities() const;  // 3|V|, m/s
  // Per-triangle domain id in [0, domainCount()), for rendering.
  const std::vector<int>& triangleDomain() const;
  int domainCount() const;
  double time() const;  // simulated seconds
  const PreviewSettings& settings() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace drape::pd
