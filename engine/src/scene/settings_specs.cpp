// The table of every setting, in groups (SettingGroup): the scene, its mesh and fabric, contact, the run, the
// preview, the drape, the quality verdict and the output.
#include <cstdio>

#include "drape/scene/settings.h"
#include "drape/scene/stage_settings.h"

namespace drape {
namespace {

// The preview's defaults: its settings struct's (one source for each).
const PreviewStageSettings kPreview{};

std::string defaultOf(double value) {
  char out[32];
  std::snprintf(out, sizeof out, "%.17g", value);
  return out;
}

std::string defaultOf(int value) { return std::to_string(value); }

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
          {"contact.self_collision", T::Boolean, "false", "", "cloth-cloth contact: the cloth keeps off itself and crossings are pulled free"},
      }),
      section(G::Run, {
          {"solver.stage", T::Choice, "drape", "", "what --simulate runs: none (placed garment), preview (the drape's model by L-BFGS), drape "
               "(Newton from the placed garment) or full (preview, then the drape from the preview state)", -1e300, 1e300,
               {"none", "preview", "drape", "full"}},
          {"solver.max_sim_time", T::Number, "3", "s", "simulated time limit when the garment does not come to rest", 1e-4,
               1e4},
          {"solver.max_steps", T::Integer, "100000", "", "step limit", 1, 1e9},
      }),
      section(G::Preview, {
          {"solver.preview.time_step", T::Number, defaultOf(kPreview.timeStep), "s",
               "preview time step (the drape's model solved by L-BFGS at a longer step than the drape's)", 1e-5, 0.1},
          {"solver.preview.iterations", T::Integer, defaultOf(kPreview.iterations), "",
               "L-BFGS iterations per preview step (its initial Hessian: pd-dd's domain-decomposed system)", 1, 1000},
          {"solver.preview.domains", T::Integer, defaultOf(kPreview.domains), "", "METIS domains D (0: the thread count)", 0,
               4096},
          {"solver.preview.max_time", T::Number, defaultOf(kPreview.maxTime), "s",
               "longest preview of the full pipeline before the drape takes over (docs/BENCHMARKS.md)", 1e-3, 1e4},
          {"solver.preview.handoff_speed", T::Number, defaultOf(kPreview.handoffSpeed), "m/s",
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
          {"solver.newton.rest_force", T::Number, "0.025", "",
               "balance near rest: a step that starts below the rest speed iterates on (up to max_iterations) while the "
               "force its residual leaves, as a fraction of each vertex's weight (RMS), is above this", 1e-9, 1e3},
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
          {"quality.max_self_intersections", T::Integer, "0", "",
               "largest number of crossing pairs of garment triangles (sharing no vertex, seams sewn) that passes", 0, 1e9},
          {"quality.max_seam_gap", T::Number, "0.003", "m",
               "largest distance at rest between two sewn points of a seam that passes (a seam left open)", 0, 1},
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
