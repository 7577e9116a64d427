// Backward-Euler Newton drape solver (newton-drape-pizana sections 3, 5; Algorithm 1): velocity-form implicit
// Euler (eqs. 1-4) solved by Newton with a residual-decrease backtracking line search, PCG linear solves, time
// splitting, initial relaxation and an early-stop test on the 99th percentile of per-vertex kinetic energy.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "drape/model/cloth_model.h"
#include "drape/newton/energy.h"
#include "drape/newton/linear_solve.h"
#include "drape/model/step_preconditioner.h"

namespace drape::newton {

// Every paper parameter, defaults from the paper (sections 3.1, 5.1-5.4).
struct NewtonSettings {
  double tauNewton = 1e-3;        // Newton tolerance on |M(v - v_n) + h dE/dx|, kg m/s (tau_n)
  int maxNewtonIterations = 5;    // I_n
  int maxLineSearchIterations = 5;  // I_ls
  bool projectHessians = true;    // SPD membrane/bending Hessians; false = exact (may be indefinite; tests)
  LinearSolveOptions linear;      // tau_cg = 1e-2, 500 iterations, block-Jacobi PCG
  double hMax = 1e-3;             // s: the paper's; a scene's solver.newton.h_max (2 ms, docs/TRADE.md) sets it
  double hMin = 1e-8;             // s; a step that fails below this is Diverged
  double omega = 0.75;            // time-splitting factor
  int growAfterSteps = 5;         // I_s: good steps before h grows by 1/omega
  // First step, s; 0: hMax (hMax / relaxationStepDivisor with the relaxation). Not in the paper: the drape that
  // starts from the preview's state starts below its longer hMax and grows to it.
  double startStep = 0.0;
  double alpha = 5.0;             // air drag, 1/s
  double betaStretch = 1e-2;      // stretch dissipation, s
  double betaBend = 1e-1;         // bending dissipation, s
  double stitchStiffness = 1e4;   // N/m
  double pinStiffness = 1e4;      // N/m
  bool relaxation = true;         // initial relaxation (5.2)
  double relaxationTime = 0.1;    // s
  double relaxationStepDivisor = 16.0;  // the relaxation starts at h = hMax / 16
  // true: h stays at hMax / relaxationStepDivisor for the whole window; false: the window starts at that step and
  // h grows back by the usual rule (I_s good steps, 1 / omega), the paper's "initial time step" (5.2).
  bool relaxationHoldStep = false;
  double relaxationStartScale = 1e-2;   // stiffness ramp start
  // Not in the paper: a relaxation step (v_n = 0) starts its Newton iterations from the last step's velocity, scaled
  // to h, instead of from x_n: the stitches and the ramp move the garment steadily, so the last motion predicts this
  // one. Only the first iterate changes, not the step's equations (its velocities are still zeroed after it).
  bool relaxationGuess = true;
  // Early stop: at rest once the 99th percentile of vertex speeds |v_i| stays below restSpeed for earlyStopWindow.
  // A speed, not a kinetic energy: 0.5 m |v|^2 per vertex shrinks with the fabric's density and the mesh's spacing,
  // so an energy threshold took a light or finely meshed garment for at rest while it still moved.
  double restSpeed = 0.02;              // m/s; 0: never at rest
  // Balance near rest: a step that starts below the rest speed iterates on (up to I_n, as restAwareConvergence) while
  // the force its residual leaves, |b_i| / h per vertex against the vertex's weight, is above this in RMS. The early
  // stop itself stays a speed: the unbalanced force of a step (NewtonStepReport::forceRms) has a floor at long steps
  // that Newton's line search cannot lower (docs/BENCHMARKS.md, "A drape at rest in seconds").
  double restForce = 0.025;
  double earlyStopWindow = 0.1;         // s
  double restPercentile = 0.99;         // the percentile of the speeds, velocity errors and reported kinetic energies
  // Rest-aware convergence (not in the paper): near rest, an absolute tau_n lets a step end with a momentum residual
  // r whose velocity error (r_i / m_i per vertex) is larger than the motion the early stop waits to die out, and the
  // accepted errors keep the garment creeping (the A-line skirt from the preview's state, for seconds at tau_n 1e-3).
  // With this on, a step that starts near rest (the speed percentile below restAwareFactor x restSpeed; not in the
  // relaxation, whose velocities are zeroed) and ends below tau_n iterates on while the residual's velocity error,
  // percentile(|r_i| / m_i), is above restSpeed, up to I_n iterations; at I_n a step below tau_n is accepted as
  // before (no time split).
  bool restAwareConvergence = true;
  double restAwareFactor = 10.0;
  // Production speed-ups (section 6), each a switch so benchmarks can measure it (none changes the results
  // beyond round-off). Closed-form dihedral-angle gradient instead of automatic differentiation in bending.
  bool closedFormBending = true;
  // Precomputed stencil -> 3x3 block slot map (6.1): Hessian assembly writes by index, no search.
  bool cachedBlockMap = true;
  // Stencil colouring (6.5): force and Hessian assembly in parallel (TBB) colour by colour, no atomics.
  bool parallelAssembly = true;
  bool foldDissipation = true;  // AssemblyOptions::foldDissipation: one scatter per triangle / hinge
  bool batchedGradients = true;  // AssemblyOptions::batchedGradients: gradient passes eight stencils at a time
  // Reverse Cuthill-McKee renumbering of the matrix block rows (6.4): locality of SpMV and Hessian writes.
  bool reorderDofs = true;
  // (Warm-started PCG, fused parallel PCG kernels and mixed precision are switches of `linear`.)
  // Hessian reuse (not in the paper): the first Newton iteration of a step may solve with the elastic part of an
  // earlier step's Hessian (membrane, bending, dissipations, air drag, stitches, pins; contact, friction and the
  // drag spring are always fresh) when that part is at most this many steps old, the step size is unchanged and
  // the previous step converged in one iteration. The residual test is unchanged, so a step still ends below
  // tau_n; a reused iteration whose line search had to shorten the step is followed by a fresh one (even below
  // tau_n), and a step needing a second iteration assembles afresh. 0 = always fresh (the paper).
  int hessianReuseSteps = 4;
  // Inexact-Newton forcing (not in the paper): the PCG of an iteration whose residual is r stops at the relative
  // tolerance max(tau_cg, min(0.5, cgForcing * tau_n / r)), i.e. once the linear residual is a fraction cgForcing
  // of the Newton tolerance, instead of always reducing it 1 / tau_cg times. The step still ends below tau_n.
  // 0 = off (always tau_cg).
  double cgForcing = 0.0;
  // Exact, not a trade (no scene setting; tests compare both): a relaxation step starts at x_n with zero
  // velocities, so its first gradient of the membrane and the bending is the one the previous step's accepted
  // line-search pass recorded (energy.h, addRecordedStepStartGradient).
  bool stepStartGradients = true;
  // Two-level PCG (coarse_space.h; not in the paper): vertices per coarse aggregate, 0 = block-Jacobi alone (the
  // paper).
  int coarseAggregate = 16;
  // The coarse matrix is a preconditioner: the PCG meets tau_cg with a somewhat stale one too. Lagged (default), it
  // is factorised from the matrix of a step's first Newton iteration when the elastic Hessian was assembled afresh
  // there (hessianReuseSteps), or when h changed, and kept through later Newton iterations and the contact, friction
  // and drag-spring blocks that change in every iteration. Not lagged: refactorised for every solve whose matrix
  // changed (every solve in scenes with contact). Lagged, it is factorised several times less often, with no more
  // PCG iterations.
  bool coarseLagged = true;
  // The coarse level is used from the solve after one that needed at least this many PCG iterations with
  // block-Jacobi alone, until a two-level solve needs fewer than a quarter of it (0: always). On a soft garment
  // with contact (the default scene: ~20 iterations per step) its cost per solve outweighs the iterations saved.
  int coarseFromIterations = 30;
  // Coupled groups (coupled_groups.h; not in the paper): vertices the matrix couples at least this strongly
  // (relative to their diagonal blocks), such as a stitch's two ends, are preconditioned as one block of up to four
  // vertices. 0 = off (block-Jacobi alone, the paper). They are used from the solve after one that needed at least
  // coupledFromIterations PCG iterations until one with them needs fewer than half of that (0: always): at the
  // drape's long steps after the preview (a median of ~100 iterations per solve on the t-shirts) they halve the
  // iterations; at h = 1 ms (~20-40) finding and refreshing them costs what they save.
  double coupledThreshold = 0.6;
  int coupledFromIterations = 60;
};

// The quasi-Newton inner solve of a step (the preview; quasi_newton_step.cpp): L-BFGS on the same incremental
// potential as Newton's, its initial Hessian a model::StepPreconditioner (Liu, Bouaziz and Kavan 2017), with a backtracking
// Armijo line search. A step ends once the momentum residual is below tau_n or after maxIterations iterations, where
// it is kept as it is (the preview solves inexactly).
struct QuasiNewtonSettings {
  int maxIterations = 4;            // L-BFGS iterations per step
  int history = 8;                  // curvature pairs kept (m)
  int maxLineSearchIterations = 10;  // halvings of the step length
  double armijo = 1e-4;             // sufficient decrease, c1
};

class PinSprings;
class CoarseSpace;
class CoupledGroups;

enum class NewtonStatus { Converged, MaxIterations, Diverged, Cancelled };
const char* toString(NewtonStatus status);

struct NewtonStepReport {
  NewtonStatus status = NewtonStatus::Converged;
  double time = 0.0;          // simulated time after the step, s
  double h = 0.0;             // step actually taken, s
  int newtonIterations = 0;   // over all attempts of this step
  int cgIterations = 0;       // over all attempts
  int splits = 0;             // time-split retries in this step
  double residual = 0.0;      // final Newton residual, kg m/s
  std::vector<double> residualHistory;  // residual before the first and after every Newton iteration (last attempt)
  double kineticPercentile = 0.0;  // 99th percentile of per-vertex kinetic energy, J
  double speedPercentile = 0.0;    // 99th percentile of vertex speeds, m/s (the early stop's measure)
  bool atRest = false;        // early-stop criterion met (5.4)
  bool relaxing = false;      // step was inside the relaxation window
  std::vector<std::string> energies;  // names of the energies used
  // Wall time spent in this step (all attempts), seconds: Hessian assembly (the first iteration's includes the
  // gradient at the same x, assembled in the same pass), the other gradient (residual) evaluations, linear solves.
  double hessianSeconds = 0.0;
  double gradientSeconds = 0.0;
  double linearSolveSeconds = 0.0;
  bool hessianReused = false;  // the first iteration solved with a reused elastic Hessian (hessianReuseSteps)
  int recordedGradients = 0;   // energies whose first gradient came from the last step's pass (stepStartGradients)
  int coarseSolves = 0;        // linear solves with the two-level preconditioner (coarseAggregate)
  int coarseFactorizations = 0;  // coarse matrices factorised for them (coarseLagged)
  int coupledSolves = 0;       // linear solves with coupled groups (coupledThreshold)
  // Equilibrium at the step's end: the unbalanced force on each vertex, -dE/dx = (M (v - v_n) + b) / h with b the
  // step's final momentum residual, as a fraction of the vertex's weight m_i |g| (standard gravity when the model has
  // none): its largest value and its root mean square over the vertices with mass; and the largest vertex
  // displacement of the step, m.
  double forceMax = 0.0;
  double forceRms = 0.0;
  double displacementMax = 0.0;
  // Wall time of the energies' per-step set-up (beginStep: contact candidates, friction's lagged contact set), s.
  double contactQuerySeconds = 0.0;
  bool quasiNewton = false;    // solved by L-BFGS (setQuasiNewton): newtonIterations counts its iterations
  int lineSearchEvaluations = 0;  // potential evaluations of the line searches (quasi-Newton)
};

class NewtonSolver {
 public:
  // Builds only the energies the model needs; extra energies (contact, friction) are appended and owned.
  // Throws std::invalid_argument on inconsistent sizes or degenerate rest triangles.
  NewtonSolver(model::ClothModel model, NewtonSettings settings, std::vector<std::unique_ptr<Energy>> extra = {});
  ~NewtonSolver();

  // Advances one step (with internal time-split retries). Never throws for numerical trouble: a failure
  // keeps the last good state and reports Diverged.
  NewtonStepReport step();
  void requestCancel() { m_cancel.store(true); }
  void clearCancel() { m_cancel.store(false); }
  // A spring of settings.pinStiffness pulling vertex towards target, metres (a grabbed vertex following the
  // cursor); vertex < 0 releases it. The "drag" energy exists from the first call on.
  void setDrag(int vertex, const Eigen::Vector3d& target);
  // From the next step on, solves every step by L-BFGS with `preconditioner` as its initial Hessian instead of by
  // Newton and PCG (the preview stage's strategy, sim/newton_stage.h); null: Newton. A step that the quasi-Newton solve leaves
  // above tau_n after its iterations is kept (MaxIterations is not a failure there).
  void setQuasiNewton(std::shared_ptr<model::StepPreconditioner> preconditioner, QuasiNewtonSettings settings = {});

  const Eigen::VectorXd& positions() const { return m_x; }   // 3|V|, metres
  const Eigen::VectorXd& velocities() const { return m_v; }  // 3|V|, m/s
  const Eigen::VectorXd& masses() const { return m_mass; }   // |V|, kg
  double time() const { return m_time; }
  double currentStep() const { return m_h; }
  bool atRest() const { return m_restSince >= 0.0 && m_time - m_restSince >= m_settings.earlyStopWindow; }
  std::vector<std::string> energyNames() const;
  const std::vector<std::unique_ptr<Energy>>& energies() const { return m_energies; }
  NewtonSettings& settings() { return m_settings; }

  // The assembly switches of the settings, as handed to the energies in StepContext.
  AssemblyOptions assemblyOptions() const;
  // Sum of all energies at x (joules), as of the last beginStep.
  double totalEnergy(const Eigen::VectorXd& x) const;
  // 99th (settings) percentile of 0.5 m_i |v_i|^2 over vertices.
  double kineticEnergyPercentile() const;
  // 99th (settings) percentile of |v_i| over vertices with mass.
  double speedPercentile() const;
  // restAwareConvergence: whether the settings' percentile of |b_i| / m_i is below the rest speed
  // (always true for a step that does not start near rest).
  bool residualBelowRest(const Eigen::VectorXd& b) const;

 private:
  // Attempts one step of size h from the current state. Fills x, v and the report's counters.
  NewtonStatus attempt(double h, double scale, Eigen::VectorXd& x, Eigen::VectorXd& v, NewtonStepReport& report);
  // The same by L-BFGS (setQuasiNewton; quasi_newton_step.cpp).
  NewtonStatus attemptQuasiNewton(double h, double scale, Eigen::VectorXd& x, Eigen::VectorXd& v,
                                  NewtonStepReport& report);
  // Per vertex (|V|, N/m): the largest eigenvalue of the diagonal Hessian block at x of the terms assembled afresh
  // in every iteration (contact, friction, the drag spring); 0 where they add none. Assembles into m_freshHessian.
  void freshVertexStiffness(const Eigen::VectorXd& x, Eigen::VectorXd& k);
  // Fills the report's forceMax, forceRms and displacementMax for the accepted step from x_n, v_n (m_x, m_v) to x, v
  // with final momentum residual m_lastResidual.
  void measureEquilibrium(const Eigen::VectorXd& x, const Eigen::VectorXd& v, NewtonStepReport& report) const;
  // b = M (v_n - v) - h dE/dx(x) (eq. 4); momentumResidual takes the gradient g = dE/dx already summed.
  void residual(const Eigen::VectorXd& x, const Eigen::VectorXd& v, double h, Eigen::VectorXd& b) const;
  void momentumResidual(const Eigen::VectorXd& g, const Eigen::VectorXd& v, double h, Eigen::VectorXd& b) const;

  model::ClothModel m_model;
  NewtonSettings m_settings;
  std::vector<std::unique_ptr<Energy>> m_energies;
  PinSprings* m_drag = nullptr;  // owned by m_energies
  BlockMatrix m_matrix;
  Eigen::VectorXd m_mass;
  Eigen::VectorXd m_x, m_v;
  double m_time = 0.0;
  double m_h = 0.0;
  int m_goodSteps = 0;
  double m_restSince = -1.0;
  bool m_nearRest = false;  // this step started near rest (restAwareConvergence)
  bool m_slowStart = false;  // ... and below the rest speed: its residual must also leave the forces balanced
  // Assembles the first iteration's gradient g and Hessian (m_matrix, without the mass term unless
  // m_matrixReady says it is already there) at x: the elastic part reused when allowed (returns true), otherwise
  // assembled and saved for reuse.
  // atStepStart: x is the step's start x_n and the velocities are zero (recorded gradients apply).
  bool assembleFirstIteration(const Eigen::VectorXd& x, double h, bool atStepStart, Eigen::VectorXd& g,
                              int& recordedGradients);
  // The Hessian of a later iteration at x, saving the elastic part for reuse.
  void assembleHessian(const Eigen::VectorXd& x, double h);
  // Marks m_matrix's static values as the reusable elastic Hessian for step h (settings.hessianReuseSteps > 0),
  // copying them when fresh terms will be added on top (otherwise the matrix itself keeps them: m_matrixReady).
  void saveElasticHessian(double h);
  // Whether the Newton matrix gets blocks beyond the elastic terms' in every iteration (contact, friction, the drag
  // spring: energies after m_elasticCount, or dynamic entries).
  bool hasFreshTerms() const;

  // m_energies[0, m_elasticCount) are the solver's own smooth terms (reusable Hessian); the rest (contact,
  // friction, the drag spring) are assembled afresh every iteration.
  size_t m_elasticCount = 0;
  std::vector<Eigen::Matrix3d> m_elasticHessian;  // static blocks of the elastic terms' Hessian, storage order
  double m_elasticHessianH = 0.0;                 // step size it was assembled for (0: none saved)
  int m_elasticHessianAge = 0;                    // steps it has been reused
  bool m_elasticHessianCopied = false;            // m_elasticHessian holds it (else only m_matrix does)
  // m_matrix is the elastic Hessian of m_elasticHessianH plus the mass term M / h^2 of that h and nothing else (no
  // fresh terms): a reusing step solves with it as it stands, without copying a saved Hessian in.
  bool m_matrixReady = false;
  // The PCG's preparation of m_matrix (inverse diagonal blocks, float copy), kept while m_matrixReady.
  PcgCache m_pcgCache;
  int m_lastNewtonIterations = 0;                 // Newton iterations of the last accepted step (last attempt)
  // Velocity change of the last accepted step (3|V|, m/s) and its h (s): the PCG initial guess of the next step.
  Eigen::VectorXd m_lastDv;
  double m_lastDvH = 0.0;
  // Two-level PCG: the coarse space (settings.coarseAggregate > 0), and whether m_matrix's static values changed
  // since its last factorisation (fresh elastic assembly) and for which h it was factorised.
  std::unique_ptr<CoarseSpace> m_coarse;
  bool m_coarseStale = true;
  bool m_useCoarse = false;  // coarseFromIterations: the last solves needed many iterations
  double m_coarseH = 0.0;
  // Coupled groups (settings.coupledThreshold > 0): the h they were found at (0: none yet), whether m_matrix's
  // static values changed since their inverses were computed, and whether the last solves needed many iterations.
  std::unique_ptr<CoupledGroups> m_coupled;
  double m_coupledH = 0.0;
  bool m_coupledStale = true;
  bool m_useCoupled = false;
  std::atomic<bool> m_cancel{false};
  Eigen::VectorXd m_lastResidual;  // the momentum residual b of the last attempt's final iterate
  std::shared_ptr<model::StepPreconditioner> m_quasiNewton;  // setQuasiNewton
  QuasiNewtonSettings m_qnSettings;
  BlockMatrix m_freshHessian;  // freshVertexStiffness's diagonal-pattern matrix
};

}  // namespace drape::newton
