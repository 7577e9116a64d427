// The table of every setting, in groups (SettingGroup): the scene, its mesh and fabric, contact, the run, the
// preview, the drape, the quality verdict and the output.
#include "drape/scene/settings.h"

namespace drape {
namespace {

// The rows of one group, each marked with it.
std::vector<SettingSpec> section(SettingGroup group, std::vector<SettingSpec> rows) {
  for (SettingSpec& row : rows) row.group = group;
  return rows;
}

std::vector<SettingSpec> concat(std::initializer_list<std::vector<SettingSpec>> sections) {
  std::vector<SettingSpec> all;
  for (const auto& rows : sections) all.insert(all.end(), rows.begin(), rows.end());
  return all;
}

}  // namespace

// Rows leave out the trailing fields they do not need (bounds, choices), which keep their defaults.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
const std::vector<SettingSpec>& Settings::specs() {
  using T = SettingType;
  using G = SettingGroup;
  // One row a setting, grouped by section (the formatter would give each field of a row a line of its own).
  // clang-format off
  static const std::vector<SettingSpec> table = concat({
      section(G::Scene, {
          {"pattern", T::Text, "", "", "sewing pattern file (GarmentCode JSON), relative to the scene file"},
          {"avatar.file", T::Text, "", "", "avatar or collider mesh (obj, glb, gltf, fbx, ply, stl); empty: none"},
          {"avatar.units", T::Choice, "m", "", "length unit of the avatar file", -1e300, 1e300, {"m", "cm", "mm", "in"}},
          {"sim.gravity", T::Number, "-9.81", "m/s^2", "gravity along y", -1000, 1000},
          {"grading.scale", T::Number, "1", "", "a graded size: the whole pattern, panels and their placement, scaled "
               "uniformly about the pattern's origin (docs/FORMATS.md, \"Sizes\")", 0.25, 4},
          {"placement.translate", T::Vector3, "0,0,0", "m", "moves the placed garment, every panel, by this vector: for "
               "a pattern laid out around another body's origin", -100, 100},
          {"placement.fit", T::Boolean, "true", "", "fits a pattern laid out around another body to the avatar: panel "
               "groups (torso, sleeves, skirt) moved rigidly onto the avatar's landmarks, then panels inside the body moved out "
               "(docs/FORMATS.md)"},
      }),
      section(G::Mesh, {
          {"mesh.target_edge_length", T::Number, "0.01", "m", "target triangle edge length of the garment mesh", 1e-4,
               1.0},
          {"mesh.conforming_seams", T::Boolean, "true", "", "stitched edges sampled alike and sewn vertex to vertex; "
               "false: each edge at its own spacing, seams sewn vertex to edge point (non-conforming)"},
      }),
      section(G::Fabric, {
          {"fabric.preset", T::Text, "cotton_shirting", "", "default fabric of every panel (a file in assets/fabrics)"},
          {"fabric.stretch_warp", T::Number, "", "N/m", "override: stretch stiffness along the warp (0 holds nothing together)", 1e-3, 1e7},
          {"fabric.stretch_weft", T::Number, "", "N/m", "override: stretch stiffness along the weft (0 holds nothing together)", 1e-3, 1e7},
          {"fabric.shear", T::Number, "", "N/m", "override: in-plane shear stiffness", 0, 1e7},
          {"fabric.bend_warp", T::Number, "", "N m", "override: bending stiffness about the weft axis", 0, 1},
          {"fabric.bend_weft", T::Number, "", "N m", "override: bending stiffness about the warp axis", 0, 1},
          {"fabric.density", T::Number, "", "kg/m^2", "override: areal density", 1e-4, 10},
          {"fabric.friction", T::Number, "", "", "override: Coulomb friction coefficient", 0, 5},
          {"fabric.thickness", T::Number, "", "m", "override: thickness (contact offset)", 0, 0.05},
          {"fabric.damping", T::Number, "", "s", "override: stretch dissipation beta_s of the drape", 0, 10},
      }),
      section(G::Contact, {
          {"contact.stiffness", T::Number, "1000", "N/m",
               "penalty stiffness of avatar and cloth contact (paper: 1e2, which lets a tight garment rest on the skin)", 0, 1e9},
          {"contact.thickness", T::Number, "", "m", "override: contact thickness (default: the fabric's thickness, at least 2 mm)", 0, 0.1},
          {"contact.friction", T::Boolean, "true", "", "Coulomb friction (off, or fabric friction 0: no friction term)"},
          {"contact.friction_majorizer", T::Boolean, "true", "",
               "drape: a step's first Newton iteration takes friction's isotropic majorizer instead of its Hessian, so that a "
               "contact that should stick cannot overshoot and chatter from step to step"},
          {"contact.avatar_features", T::Boolean, "true", "",
               "the avatar's sharp points (radius of curvature below mean garment edge^2 / (4 thickness)) push the garment's "
               "triangles, not only its vertices (Newton drape)"},
          {"contact.self_collision", T::Boolean, "false", "", "cloth-cloth contact (builds the self-collision BVH)"},
      }),
      section(G::Run, {
          {"solver.stage", T::Choice, "drape", "", "what --simulate runs: none (placed garment), preview (PD-DD), drape "
               "(Newton from the placed garment) or full (preview, then the drape from the preview state)", -1e300, 1e300,
               {"none", "preview", "drape", "full"}},
          {"solver.max_sim_time", T::Number, "3", "s", "simulated time limit when the garment does not come to rest", 1e-4,
               1e4},
          {"solver.max_steps", T::Integer, "100000", "", "step limit", 1, 1e9},
      }),
      section(G::Preview, {
          {"solver.preview.method", T::Choice, "projective", "", "what the preview solves: projective (pd-dd's constraint "
               "model; the other solver.preview settings) or quasi_newton (the drape's own model and rest states, by L-BFGS "
               "whose initial Hessian is the PD-DD system; qn_* settings; docs/BENCHMARKS.md, \"A preview on the drape's "
               "model\")", -1e300, 1e300, {"projective", "quasi_newton"}},
          {"solver.preview.qn_time_step", T::Number, "0.008333333333333333", "s", "quasi-Newton preview: time step", 1e-5,
               0.1},
          {"solver.preview.qn_iterations", T::Integer, "4", "", "quasi-Newton preview: L-BFGS iterations per step", 1,
               1000},
          {"solver.preview.time_step", T::Number, "0.0020833333333333333", "s",
               "preview time step h (the paper: 1/120 s; 1/480 s keeps stiff, light garments on the body, docs/ENGINE.md)", 1e-5,
               0.1},
          {"solver.preview.tolerance", T::Number, "1e-3", "", "L-G convergence: max move / scene size", 1e-9, 1},
          {"solver.preview.max_iterations", T::Integer, "30", "", "cap on L-G iterations per step", 1, 10000},
          {"solver.preview.anderson_window", T::Integer, "0", "",
               "Anderson acceleration of the L-G iterations over this many past iterates (0: off, the paper's plain loop)", 0,
               50},
          {"solver.preview.max_halvings", T::Integer, "2", "",
               "a step whose L-G loop hits the cap is redone at h/2, at most this many halvings below time_step (0: never)", 0,
               20},
          {"solver.preview.grow_after_steps", T::Integer, "10", "", "converged steps before a halved time step doubles back",
               1, 100000},
          {"solver.preview.domains", T::Integer, "0", "", "METIS domains D (0: the thread count)", 0, 4096},
          {"solver.preview.local_step", T::Choice, "gauss_seidel", "", "local step", -1e300, 1e300,
               {"gauss_seidel", "jacobi"}},
          {"solver.preview.contact_solve", T::Choice, "factor", "", "collision-aware global solve", -1e300,
               1e300, {"dual_then_pcg", "pcg", "dual_cg_then_pcg", "factor"}},
          {"solver.preview.pcg_tolerance", T::Number, "1e-6", "", "relative residual of the collision-aware solve (eq. 14)",
               1e-12, 1},
          {"solver.preview.hold_contact_targets", T::Boolean, "false", "",
               "avatar contact targets fixed within a step once found"},
          {"solver.preview.hold_targets_step", T::Number, "0.0020833333333333333", "s",
               "before the garment is sewn, avatar contact targets are held within steps no longer than this (0: only once "
               "sewn)", 0, 1},
          {"solver.preview.sewn_gap", T::Number, "0.0005", "m",
               "once every stitch gap is below this, contact targets are held within a step and friction takes the cloth's "
               "tension as load, once they have stayed so for sewn_time (0: never)", 0, 1},
          {"solver.preview.sewn_time", T::Number, "0.1", "s",
               "how long every stitch gap must stay below sewn_gap before the garment counts as sewn", 0, 1e4},
          {"solver.preview.sewn_local_step", T::Choice, "jacobi", "", "local step once the garment is sewn", -1e300,
               1e300, {"gauss_seidel", "jacobi"}},
          {"solver.preview.assembly_edge_length", T::Number, "0.02", "m",
               "a garment meshed at least 1.5x finer is first sewn by the preview on a mesh of this edge length, then carried "
               "over to its own mesh (0: never)", 0, 1},
          {"solver.preview.contact_targets", T::Choice, "reproject", "",
               "avatar contact targets: half-spaces fixed per step, or re-projected every L-G iteration", -1e300, 1e300,
               {"step_planes", "reproject"}},
          {"solver.preview.friction_load", T::Choice, "inertial", "",
               "normal load bounding friction: inertial prediction, or collision-free solve (incl. cloth tension)", -1e300,
               1e300, {"inertial", "collision_free"}},
          {"solver.preview.shear_model", T::Choice, "stretch", "",
               "what resists shear in the strain constraints: the stretch weights (pd-dd; too stiff in shear, converges) or "
               "the fabric's shear stiffness (accurate when converged; under-converged it over-shears)", -1e300, 1e300, {"fabric", "stretch"}},
          {"solver.preview.failure_strain", T::Number, "5", "",
               "a preview triangle stretched past this strain (5 = 6x its rest length) after the quasi-static start (during "
               "it: past 4x this for 3 ms) is a tear (mostly the body through the cloth): the preview starts over softer "
               "when retry_courant_limit says so, else the full pipeline, or a drape asked to start from that preview state, "
               "starts the drape from the placed garment instead, and a preview run alone goes on and says its result is wrong "
               "(0: never)", 0, 1e6},
          {"solver.preview.relaxation_time", T::Number, "0.05", "s",
               "velocities zeroed after every step until this scene time (quasi-static assembly)", 0, 1e4},
          {"solver.preview.courant_limit", T::Number, "0", "",
               "the preview softens a fabric in stretch and shear until an elastic wave crosses at most this many mean edge "
               "lengths per step (sqrt(stretch / density) time_step / edge; the default t-shirt in jersey: 4.7, in the "
               "other presets 18-26, whose previews tear at their own stiffness); the drape keeps the fabric's own "
               "stiffness (0: the preview too; see pipeline_courant_limit)", 0, 1e6},
          {"solver.preview.pipeline_courant_limit", T::Number, "5", "",
               "courant_limit for the full pipeline's preview (the softer of the two when both are set): the drape that "
               "follows it restores the fabric's stiffness; such a softened preview hands over after softened_max_time "
               "(0: courant_limit alone)", 0, 1e6},
          {"solver.preview.softened_max_time", T::Number, "0.075", "s",
               "longest preview stage of the full pipeline when its fabric is softened (courant_limit, "
               "pipeline_courant_limit), if shorter than max_time: a softened preview sags and slides more than the fabric "
               "would (the A-line skirt 4 cm down the hips by 0.5 s)",
               1e-3, 1e4},
          {"solver.preview.retry_courant_limit", T::Number, "5", "",
               "a preview that tears (solver.preview.failure_strain) with a fabric whose Courant number is above this (see "
               "courant_limit, which must be 0 or above this) starts over once from the placed garment with courant_limit at "
               "this, before a tear gives it up (0: never)", 0, 1e6},
          {"solver.preview.retry_without_held_targets", T::Boolean, "true", "",
               "a preview that tears when no softer retry applies (retry_courant_limit) starts over once from the placed "
               "garment with its avatar contact targets never held before the garment is sewn (hold_targets_step 0): held "
               "targets can lock a seam pulled across the body"},
          {"solver.preview.handoff_strain", T::Number, "2", "",
               "a full pipeline's preview about to hand over a triangle stretched past this (2 = 3x its rest length) starts "
               "over as after a tear when retry_without_held_targets still applies; else it hands over (0: never)", 0, 1e3},
          {"solver.preview.sd_iterations", T::Integer, "1", "", "dual steepest-descent updates before PCG (eq. 24)", 1,
               1000},
          {"solver.preview.ccd", T::Boolean, "true", "", "CCD of the vertex paths against the avatar"},
          {"solver.preview.max_time", T::Number, "0.5", "s",
               "longest preview stage (full pipeline), counted again when the garment's own mesh takes over from the coarse "
               "assembly; a later hand-over leaves the drape more to undo (docs/BENCHMARKS.md)",
               1e-3, 1e4},
          {"solver.preview.rest_speed", T::Number, "0.01", "m/s",
               "the preview is settled when the 99th percentile of vertex speeds falls below this", 0, 100},
          {"solver.preview.handoff_speed", T::Number, "0.1", "m/s",
               "full pipeline: the drape takes over once the 99th percentile of vertex speeds stays below this for 0.1 s",
               0, 100},
      }),
      section(G::Drape, {
          {"solver.newton.tolerance", T::Number, "1e-3", "kg m/s",
               "Newton tolerance tau_n on the momentum residual (below 1e-6 the steps of a garment cannot reach it and split "
               "down to nothing)", 1e-6, 1e3},
          {"solver.newton.max_iterations", T::Integer, "5", "", "Newton iterations per step attempt I_n", 1, 1000},
          {"solver.newton.line_search_iterations", T::Integer, "5", "", "backtracking halvings I_ls", 0, 60},
          {"solver.newton.h_max", T::Number, "2e-3", "s", "largest time step h_max (the paper: 1e-3, slower and no closer to the reference drape: docs/TRADE.md)", 1e-6, 0.1},
          {"solver.newton.omega", T::Number, "0.75", "", "time-splitting factor omega", 0.05, 0.99},
          {"solver.newton.grow_after_steps", T::Integer, "5", "", "good steps before h grows back I_s", 1, 1000},
          {"solver.newton.relaxation", T::Boolean, "true", "", "initial relaxation (the first 0.1 s: velocities zeroed, stiffness ramped, h from h_max/16)"},
          {"solver.newton.relaxation_step", T::Choice, "grow", "",
               "relaxation time step: hold h_max/16 for the whole window, or start at h_max/16 and grow back as after a split",
               -1e300, 1e300, {"hold", "grow"}},
          {"solver.newton.relaxation_guess", T::Boolean, "true", "",
               "a relaxation step starts its Newton iterations from the last step's velocity instead of zero (the step's "
               "equations and its zeroed velocities are unchanged)"},
          {"solver.newton.relaxation_after_preview", T::Boolean, "false", "",
               "initial relaxation also when the drape starts from the preview's state (seams already closed)"},
          {"solver.newton.h_max_factor_after_preview", T::Number, "10", "",
               "the drape that starts from the preview's state starts at h_max and grows (as after a time split) up to this "
               "many times h_max: it settles a garment already near rest, where the step barely moves the result (1: the step "
               "of a drape from the placed garment)",
               1, 100},
          {"solver.newton.rest_speed", T::Number, "0.02", "m/s",
               "early stop: the drape is at rest when the 99th percentile of vertex speeds stays below this for "
               "early_stop_window (0: never)", 0, 10},
          {"solver.newton.rest_aware_convergence", T::Boolean, "true", "",
               "a step below tau_n iterates on (up to max_iterations) while its residual's velocity error is above the rest "
               "speed: near rest tau_n alone accepts errors that keep the garment creeping"},
          {"solver.newton.early_stop_window", T::Number, "0.1", "s", "early stop: time the rest speed must hold", 0, 10},
          {"solver.cg.tolerance", T::Number, "1e-2", "",
               "PCG relative tolerance tau_cg (below 1e-6 the single-precision preconditioner cannot reach it and Newton's steps "
               "split down to nothing)", 1e-6, 0.9},
          {"solver.cg.max_iterations", T::Integer, "500", "", "PCG iteration cap", 1, 1e6},
          {"solver.cg.preconditioner", T::Choice, "block_jacobi", "", "PCG preconditioner", -1e300, 1e300,
               {"none", "diagonal", "block_jacobi", "incomplete_cholesky", "cholmod_direct"}},
          {"solver.cg.mixed_precision", T::Boolean, "true", "",
               "PCG in single precision (derivatives, the Newton residual and the line search stay double)"},
          {"solver.cg.forcing", T::Number, "0", "",
               "inexact Newton: PCG stops once its residual is this fraction of tau_n (relative tolerance at most 0.5, at "
               "least solver.cg.tolerance); 0: always solver.cg.tolerance", 0, 1},
          {"solver.cg.warm_start", T::Boolean, "true", "", "PCG starts from the last step's velocity change"},
          {"solver.cg.coarse_aggregate", T::Integer, "16", "",
               "two-level PCG: vertices per coarse aggregate (fused PCG; 0 or 1: block-Jacobi alone)", 0, 100000},
          {"solver.cg.coarse_from_iterations", T::Integer, "30", "",
               "two-level PCG from a solve needing this many block-Jacobi iterations (until below a quarter; 0: always)", 0,
               1e6},
          {"solver.cg.coarse_lagged", T::Boolean, "true", "",
               "two-level PCG: the coarse matrix is factorised when the elastic Hessian is assembled afresh at a step's start "
               "or h changes, and kept through contact changes and later Newton iterations (false: refactorised for every "
               "changed matrix)"},
          {"solver.cg.coupled_groups", T::Number, "0.6", "",
               "block-Jacobi inverts up to four vertices as one block where the matrix couples them at least this strongly "
               "relative to their diagonal blocks (a stitch's two ends; fused PCG; 0: off)", 0, 1},
          {"solver.cg.coupled_from_iterations", T::Integer, "60", "",
               "coupled groups from a solve needing this many PCG iterations (until one with them needs fewer than half; 0: "
               "always)", 0, 1e6},
          {"solver.newton.hessian_reuse_steps", T::Integer, "4", "",
               "steps the elastic part of the Hessian may be reused by a step's first Newton iteration (0: always fresh)", 0,
               1000},
          {"solver.damping.air", T::Number, "5", "1/s", "air drag alpha", 0, 1e3},
          {"solver.damping.bend", T::Number, "1e-1", "s", "bending dissipation beta_b", 0, 10},
          {"solver.stitch_stiffness", T::Number, "1e4", "N/m", "zero-length stitch spring stiffness", 0, 1e9},
          {"solver.pin_stiffness", T::Number, "1e4", "N/m", "pin spring stiffness", 0, 1e9},
      }),
      section(G::Quality, {
          {"quality.max_strain", T::Number, "1", "", "largest triangle stretch that passes (0.05 = 5 %)", 0, 100},
          {"quality.max_inside_fraction", T::Number, "0.01", "",
               "largest fraction of garment vertices inside a collider that passes", 0, 1},
          {"quality.max_penetration_depth", T::Number, "0", "m",
               "deepest garment vertex inside a collider that passes (0: the contact thickness)", 0, 1},
          {"quality.near_skin_distance", T::Number, "0.001", "m",
               "a garment vertex nearer than this to a collider's surface, or inside, counts as near the skin", 0, 0.1},
          {"quality.max_near_skin_fraction", T::Number, "0.01", "",
               "largest fraction of garment vertices near the skin (quality.near_skin_distance) that passes", 0, 1},
          {"quality.max_self_intersections", T::Integer, "100", "",
               "largest number of crossing pairs of garment triangles (sharing no vertex, seams sewn) that passes", 0, 1e9},
          {"quality.min_outward_fraction", T::Number, "0.98", "",
               "smallest fraction of the garment faces on a collider (within 1 cm) facing away from it that passes", 0, 1},
          {"quality.require_rest", T::Boolean, "true", "", "the run must end at rest (not at the time or step limit)"},
      }),
      section(G::Output, {
          {"camera.view", T::Choice, "three-quarter", "", "default camera preset", -1e300, 1e300,
               {"front", "back", "left", "right", "three-quarter"}},
          {"camera.fov_deg", T::Number, "35", "deg", "vertical field of view", 5, 120},
          {"camera.eye", T::Vector3, "", "m", "explicit camera position (overrides camera.view unless --view is given)"},
          {"camera.target", T::Vector3, "", "m", "point the explicit camera looks at (default: centre of the scene)"},
          {"camera.up", T::Vector3, "0,1,0", "", "up direction of the explicit camera"},
      }),
  });
  // clang-format on
  return table;
}
#pragma GCC diagnostic pop

}  // namespace drape
