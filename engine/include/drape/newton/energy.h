// Energy interface of the Newton drape solver (newton-drape-pizana section 3; PolyFEM forms, ipc-toolkit
// potentials). Every term of the incremental potential (elasticity, bending, stitches, pins, gravity, damping,
// contact, friction) is one Energy; the solver sums the list the scene needs.
#pragma once

#include <Eigen/Core>
#include <string_view>
#include <utility>
#include <vector>

#include "drape/newton/block_matrix.h"

namespace drape::newton {

// How energies with static stencils assemble gradients and Hessians (NewtonSettings switches of the production
// speed-ups, newton-drape-pizana section 6). None changes a result beyond round-off.
struct AssemblyOptions {
  bool closedFormBending = true;  // closed-form dihedral-angle gradient instead of automatic differentiation
  bool cachedBlockMap = true;     // write Hessian blocks through a precomputed stencil -> block slot map (6.1)
  bool parallel = true;           // stencil colouring, colours in sequence, one colour in parallel (6.5)
  // The membrane and hinge bending add the element Hessians (and, in addGradientAndHessian, gradients) of the
  // dissipations on the same stencils to their own before one scatter; the dissipations then add nothing there.
  bool foldDissipation = true;
  // The membrane's and the closed-form bending's gradient passes take eight stencils at a time, every quantity an
  // array over them, so that the compiler vectorises the arithmetic across stencils (not in the paper).
  bool batchedGradients = true;
};

// Quantities fixed during one time step, handed to every energy before the step's Newton iterations.
// Vectors are flat, size 3|V| (x0, y0, z0, x1, ...), metres and metres per second.
struct StepContext {
  const Eigen::VectorXd* previousPositions = nullptr;   // x_n, start of the step
  const Eigen::VectorXd* previousVelocities = nullptr;  // v_n, start of the step
  double h = 1e-3;                                      // time step, seconds
  double time = 0.0;                                    // simulated time at the start of the step, seconds
  double stiffnessScale = 1.0;  // in (0, 1]: ramp of elastic stiffness during initial relaxation (paper 5.2)
  AssemblyOptions assembly;     // speed-up switches (energies may ignore them)
};

// One term E(x) of the incremental potential, in joules, as a function of the end-of-step positions x
// (flat, size 3|V|, metres). The solver minimises 1/(2h^2)|x - x_n - h v_n|_M^2 + sum E(x) over x = x_n + h v,
// so damping terms are written as h * D((x - x_n) / h) with D a Rayleigh dissipation potential.
// Implementations must be safe to call value/addGradient/addHessian concurrently with different x only if they
// say so; the solver calls them from one thread at a time (each may parallelise internally).
class Energy {
 public:
  virtual ~Energy() = default;

  // Short stable name for reports and statistics ("membrane", "bending", "avatar_contact", ...).
  virtual std::string_view name() const = 0;

  // Called once at the start of every step (and again after a time-split retry with the new h) before any
  // value/gradient/Hessian call: lag here whatever the step keeps fixed (previous positions, friction normals,
  // active contact sets, BVH refit). ctx's pointers stay valid until the next beginStep.
  virtual void beginStep(const StepContext& ctx) { (void)ctx; }

  // E(x), joules.
  virtual double value(const Eigen::VectorXd& x) const = 0;
  // g += dE/dx (size 3|V|, newtons with a minus sign: g is the negative force).
  virtual void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const = 0;
  // H += d2E/dx2 or a symmetric positive semi-definite approximation of it (the solver needs SPD).
  // Blocks between vertex pairs listed by addCouplings land in the static pattern; others (contacts)
  // go to the dynamic part automatically through BlockMatrix::addBlock or explicitly via addDynamicBlock.
  virtual void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const = 0;
  // Whether x meets the term's own bound, which a solve stopped after a few iterations must not leave violated
  // (avatar contact: no vertex deeper inside the body than the contact thickness). The quasi-Newton step iterates on
  // while a term is not satisfied. Default: always.
  virtual bool satisfied(const Eigen::VectorXd& x) const {
    (void)x;
    return true;
  }
  // The gradient at a point no step ends at (a step's first Newton iterate x_n + h v_n: the accepted state always
  // comes from a line-search pass). Energies that record their gradient passes for the next step (the step-start
  // gradient, the dissipations' x_n data) skip the recording here. Default: addGradient.
  virtual void addGuessGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const { addGradient(x, g); }
  // Both at the same x in one pass over the stencils (the first Newton iteration of a step needs both at
  // x_n + h v_n); energies whose Hessian work already yields the gradient override it. Default: both calls.
  virtual void addGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const {
    addGradient(x, g);
    addHessian(x, h);
  }
  // The step's first Newton iterate is a prediction: x = x_n + h v_n, every vertex keeping its velocity (in the
  // relaxation, whose v_n is zero, NewtonSettings::relaxationGuess predicts the last step's velocity). There the
  // solver calls this instead. An energy may add there a symmetric positive semi-definite majorizer of its Hessian
  // (a matrix at least as stiff in every direction) where the exact Hessian lets the first Newton step overshoot a
  // solution that the loose tau_n then accepts: lagged friction does (friction.h). Default: addGradientAndHessian.
  virtual void addPredictionGradientAndHessian(const Eigen::VectorXd& x, Eigen::VectorXd& g, BlockMatrix& h) const {
    addGradientAndHessian(x, g, h);
  }

  // Relaxation steps start at x = x_n with zero velocities, where the lagged dissipations folded into an energy's
  // passes vanish. There the solver may take the energy's gradient from its last gradient pass
  // (recorded_gradient.h): adds it to g and returns true when that pass ran at x (bit for bit) with recording on,
  // otherwise adds nothing and returns false. Never call it at any other x than the step's start x_n.
  virtual bool addRecordedStepStartGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const {
    (void)x;
    (void)g;
    return false;
  }
  // Whether gradient passes record for addRecordedStepStartGradient (costs one more scatter per pass).
  virtual void setRecordStepStartGradient(bool record) { (void)record; }

  // Appends the vertex pairs (i, j), i != j, this energy couples on a topology fixed for the whole run
  // (the static block pattern, built once). Contact energies append nothing.
  virtual void addCouplings(std::vector<std::pair<int, int>>& pairs) const { (void)pairs; }
};

}  // namespace drape::newton
