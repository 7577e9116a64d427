#pragma once
// Settings of the Projective Dynamics preview solver (pd-dd-lu2025). Every trade between speed and accuracy is
// a field here; defaults follow the paper (Tab. 1) where it gives a value.
#include <Eigen/Core>
#include <algorithm>

namespace drape::pd {

// The enums that settings choose (solver.preview.*) are declared in the order of the setting's choices
// (Settings::choice, engine/src/scene/settings_specs.cpp).
enum class GlobalSolverKind { DomainDecomposed, Monolithic };  // pd-dd section 4 / baseline CHOLMOD on eq. 3
enum class LocalStepKind { GaussSeidel, Jacobi };              // pd-dd section 5 / vanilla PD baseline
// pd-dd section 6 (eq. 24 + PCG) / plain PCG / the dual solved by conjugate gradients preconditioned by the
// contact DOFs' block of K, then PCG (contact_solve.h) / a Cholesky factor of K + Delta K, updated or
// refactorised when the contact set changes (contact_factor.h; the default)
enum class ContactSolveKind { DualThenPcg, Pcg, DualCgThenPcg, Factor };
// How avatar contact targets are found in the L-G iterations of a step (avatar_collision.h): from half-spaces
// fixed per step (tangent planes at the step start's closest point, added to only where the real surface is
// violated) / re-projected onto the closest surface point (or CCD crossing) in every iteration (the first version).
enum class ContactTargetKind { StepPlanes, Reproject };
// Normal load that bounds lagged Coulomb friction: the inertial prediction's penetration of the contact planes
// (gravity and momentum only) / the collision-free solve's penetration (also the cloth's own tension pulling it
// into the body, which lets a stretch, once landed, hold itself in place by friction).
enum class FrictionLoadKind { Inertial, CollisionFree };
// What resists in-plane shear in the strain constraints (pd_system.h): a shear constraint weighted with the
// fabric's shear stiffness, the StVK membrane's small-strain energy (accurate; a soft shear mode under stiff
// stretch needs more L-G iterations) / pd-dd's strain constraint R clamp(S), shear resisted with the stretch
// weights (converges faster; 10-100 x too stiff in shear for woven fabrics).
enum class ShearModelKind { Fabric, Stretch };

// Allowed range of the principal stretch along one fabric direction (1 = rest length). Inside the range the
// strain constraint exerts no force (strain limiting); the default [1, 1] pulls towards the rest shape.
struct StretchLimits {
  double min = 1.0;
  double max = 1.0;
};

struct PreviewSettings {
  double timeStep = 1.0 / 120.0;  // h, seconds (pd-dd Tab. 1); scenes default to 1/480 s (solver.preview.time_step)
  double tolerance = 1e-3;        // max vertex move of an L-G iteration / largest extent of the cloth's box
  int maxIterations = 30;         // cap on L-G iterations per step
  int minIterations = 1;
  int andersonWindow = 0;         // > 0: Anderson acceleration of the L-G iterations over this many differences
  // A step whose L-G loop hits the cap is redone at half the time step, at most this many times below timeStep
  // (0: never, as in the paper); growAfterSteps converged steps at a level double it back. Contact on body creases
  // can keep the L-G loop from converging at 1/120 s (targets cycle between the crease's two surfaces, and the
  // unconverged steps let the garment stretch and slide off the body); a smaller step converges.
  int maxHalvings = 2;
  int growAfterSteps = 10;

  int domains = 0;                // D; 0 = the number of threads
  int threads = 0;                // 0 = all hardware threads (TBB default)
  int extraCornerStride = 0;      // > 0: every n-th duplicate boundary vertex also becomes a corner (4.3)

  GlobalSolverKind globalSolver = GlobalSolverKind::DomainDecomposed;
  LocalStepKind localStep = LocalStepKind::GaussSeidel;
  int traversalOrders = 4;        // spanning-tree DFS orders per domain, alternated between iterations (5)
  unsigned seed = 1;              // seeds the random spanning trees

  StretchLimits warpLimits;       // along pattern x
  StretchLimits weftLimits;       // along pattern y
  double shearLimit = 0.0;        // |off-diagonal stretch| allowed without force
  ShearModelKind shearModel = ShearModelKind::Stretch;  // fabric: see the enum (converges too slowly yet)
  double stitchWeight = 0.0;      // N/m per stitch; 0 = 10 x the largest stretch stiffness in the model
  double bendingScale = 1.0;      // multiplies the fabric bending stiffness
  double velocityDamping = 0.0;   // fraction of velocity removed per step, in [0, 1)
  // Seconds of scene time from the start during which velocities are zeroed after every step: the garment
  // assembles quasi-statically (stitches close the seams within a step or two and would otherwise throw the
  // panels at metres per second through each other and the body), as the drape's initial relaxation. Scenes default
  // to 0.05 s (solver.preview.relaxation_time); 0 here, so a solver built directly starts in free fall.
  double relaxationTime = 0.0;

  // Contact (pd-dd sections 6, 7.3). Avatar terms only with an avatar collider, cloth terms only with selfCollision.
  double contactThickness = 0.004;  // metres kept between cloth and avatar surface
  double contactWeight = 1e6;       // w_k of a contact constraint, N/m (pd-dd Tab. 1: kappa_c ~ 1e6); see
                                    // contactWeightFor
  double contactMargin = 0.02;      // metres beyond the thickness where vertices are watched during a step
  ContactSolveKind contactSolve = ContactSolveKind::Factor;
  int sdIterations = 1;             // dual steepest-descent updates before PCG (eq. 24), each one DD solve
  int maxDualIterations = 100;      // DualCgThenPcg: cap on dual CG iterations, each one DD solve
  int maxPcgIterations = 20;
  double pcgTolerance = 1e-6;       // relative residual of eq. 14
  bool contactWarmStart = true;     // start each collision-aware solve from the last contact forces (false: from 0)
  bool ccd = true;                  // vertex paths of the step tested against the avatar triangles (7.3)
  bool holdContactTargets = false;  // avatar contact targets fixed within a step once found (avatar_collision.h)
  // Before the garment is sewn, targets are also held within every step no longer than this (seconds; 0: none).
  // A held target pins its DOF for the step, like static friction; over a short step a vertex the stitches drag
  // moves less than the contact thickness, so the pin costs nothing and stops targets cycling on body creases.
  // Over longer steps pins tear a garment that is still closing its seams (docs/BENCHMARKS.md, "Findings worth
  // keeping"). Steps halved below it (maxHalvings) hold too. Scenes default to 1/480 s
  // (solver.preview.hold_targets_step).
  double holdTargetsStep = 0.0;
  // Once every stitch gap has stayed below sewnGap (metres) for sewnTime (seconds of scene time, ending with a
  // converged step), the garment counts as sewn, for good: from the next step on, avatar contact targets are held
  // within a step (holdContactTargets) and friction is bounded by the collision-free load
  // (FrictionLoadKind::CollisionFree, the cloth's tension included). While the seams close, the stitches' pull is
  // no real tension: it would pin stretched panels by friction where they are (switched as soon as the gaps close,
  // the default scene kept a 91 % stretch). Once sewn, the tension is real; the inertial load alone lets the
  // garment slide down the body, and unheld targets cycle on body creases, so that the paper's fixed step never
  // converged (issue 6, docs/BENCHMARKS.md). A garment without stitches is sewn after sewnTime. sewnGap 0: never
  // (both settings stay as given).
  double sewnGap = 5e-4;
  double sewnTime = 0.1;
  // The local step once sewn (localStep before). Sewn, both kinds take the same L-G iterations per step (2.2-2.7 on
  // the 10k-vertex t-shirt) and Jacobi's batched projections cost a tenth of Gauss-Seidel's sweeps; while the seams
  // close, Gauss-Seidel needs a third of Jacobi's iterations (docs/BENCHMARKS.md).
  LocalStepKind sewnLocalStep = LocalStepKind::Jacobi;
  ContactTargetKind contactTargets = ContactTargetKind::Reproject;
  FrictionLoadKind frictionLoad = FrictionLoadKind::Inertial;
  double friction = 0.0;            // Coulomb coefficient against the avatar (lagged); 0 = frictionless
  bool selfCollision = false;       // cloth-cloth vertex-triangle contact (builds the cloth BVH)
  double selfContactWeight = 1e6;   // w_k of a cloth-cloth constraint, N/m (pd-dd Tab. 1: kappa_s)

  // A grabbed vertex is pulled towards the cursor by a position constraint of this weight, N/m, solved with
  // the contacts (no refactorisation).
  double dragWeight = 1e4;
};

// Weight of a contact constraint in a model whose stiffest fabric stretches with `largestStretch` N/m: the set
// weight (the paper's 1e6 N/m), raised to 50 x the fabric's stiffness so that a contact outweighs the fabric and
// the stitches (10 x). Every fabric preset (at most 2e4 N/m) keeps 1e6; a 1e7 N/m fabric at a 0.1 s step otherwise
// converged with a vertex 51 mm inside the tablecloth's
// sphere (tests/unit/sim/solver_extremes_test.cpp).
inline double contactWeightFor(double weight, double largestStretch) {
  return std::max(weight, 50.0 * largestStretch);
}

}  // namespace drape::pd
