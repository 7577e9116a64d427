// The table of every setting. Solver settings join here as the solvers land.
#include "drape/scene/settings.h"

namespace drape {

const std::vector<SettingSpec>& Settings::specs() {
  using T = SettingType;
  static const std::vector<SettingSpec> table = {
      {"pattern", T::Text, "", "", "sewing pattern file (GarmentCode JSON), relative to the scene file"},
      {"avatar.file", T::Text, "", "", "avatar or collider mesh (obj, glb, gltf, fbx, ply, stl); empty: none"},
      {"avatar.units", T::Choice, "m", "", "length unit of the avatar file", -1e300, 1e300, {"m", "cm", "mm"}},
      {"fabric.preset", T::Text, "cotton_shirting", "", "default fabric of every panel (a file in assets/fabrics)"},
      {"fabric.stretch_warp", T::Number, "", "N/m", "override: stretch stiffness along the warp", 0, 1e7},
      {"fabric.stretch_weft", T::Number, "", "N/m", "override: stretch stiffness along the weft", 0, 1e7},
      {"fabric.shear", T::Number, "", "N/m", "override: in-plane shear stiffness", 0, 1e7},
      {"fabric.bend_warp", T::Number, "", "N m", "override: bending stiffness about the weft axis", 0, 1},
      {"fabric.bend_weft", T::Number, "", "N m", "override: bending stiffness about the warp axis", 0, 1},
      {"fabric.density", T::Number, "", "kg/m^2", "override: areal density", 1e-4, 10},
      {"fabric.friction", T::Number, "", "", "override: Coulomb friction coefficient", 0, 5},
      {"fabric.thickness", T::Number, "", "m", "override: thickness (contact offset)", 0, 0.05},
      {"fabric.damping", T::Number, "", "", "override: stretch/bend dissipation factor", 0, 10},
      {"mesh.target_edge_length", T::Number, "0.01", "m", "target triangle edge length of the garment mesh", 1e-4,
       1.0},
      {"sim.gravity", T::Number, "-9.81", "m/s^2", "gravity along y", -1000, 1000},
      // Simulation stages and limits
      {"solver.stage", T::Choice, "drape", "", "what --simulate runs: none (placed garment), preview (PD-DD), drape "
       "(Newton from the placed garment) or full (preview, then the drape from the preview state)", -1e300, 1e300,
       {"none", "preview", "drape", "full"}},
      {"solver.max_sim_time", T::Number, "3", "s", "simulated time limit when the garment does not come to rest", 1e-4,
       1e4},
      {"solver.max_steps", T::Integer, "100000", "", "step limit", 1, 1e9},
      // PD-DD preview (pd-dd-lu2025; defaults from the paper)
      {"solver.preview.time_step", T::Number, "0.008333333333333333", "s", "preview time step h", 1e-5, 0.1},
      {"solver.preview.tolerance", T::Number, "1e-3", "", "L-G convergence: max move / scene size", 1e-9, 1},
      {"solver.preview.max_iterations", T::Integer, "30", "", "cap on L-G iterations per step", 1, 10000},
      {"solver.preview.domains", T::Integer, "0", "", "METIS domains D (0: the thread count)", 0, 4096},
      {"solver.preview.local_step", T::Choice, "gauss_seidel", "", "local step", -1e300, 1e300,
       {"gauss_seidel", "jacobi"}},
      {"solver.preview.global_solver", T::Choice, "domain_decomposed", "", "global solve", -1e300, 1e300,
       {"domain_decomposed", "monolithic"}},
      {"solver.preview.contact_solve", T::Choice, "dual_then_pcg", "", "collision-aware global solve", -1e300, 1e300,
       {"dual_then_pcg", "pcg"}},
      {"solver.preview.sd_iterations", T::Integer, "1", "", "dual steepest-descent updates before PCG (eq. 24)", 1,
       1000},
      {"solver.preview.ccd", T::Boolean, "true", "", "CCD of the vertex paths against the avatar"},
      {"solver.preview.max_time", T::Number, "1", "s", "longest preview stage (full pipeline)", 1e-3, 1e4},
      {"solver.preview.rest_speed", T::Number, "0.01", "m/s",
       "the preview is settled when the 99th percentile of vertex speeds falls below this", 0, 100},
      // Newton drape (newton-drape-pizana; defaults from the paper)
      {"solver.newton.tolerance", T::Number, "1e-3", "kg m/s", "Newton tolerance tau_n on the momentum residual", 1e-12,
       1e3},
      {"solver.newton.max_iterations", T::Integer, "5", "", "Newton iterations per step attempt I_n", 1, 1000},
      {"solver.newton.line_search_iterations", T::Integer, "5", "", "backtracking halvings I_ls", 0, 60},
      {"solver.newton.h_max", T::Number, "1e-3", "s", "largest time step h_max", 1e-6, 0.1},
      {"solver.newton.omega", T::Number, "0.75", "", "time-splitting factor omega", 0.05, 0.99},
      {"solver.newton.grow_after_steps", T::Integer, "5", "", "good steps before h grows back I_s", 1, 1000},
      {"solver.newton.relaxation", T::Boolean, "true", "", "initial relaxation (0.1 s at h_max/16, stiffness ramp)"},
      {"solver.newton.early_stop_threshold", T::Number, "1e-8", "J",
       "early stop: 99th percentile of per-vertex kinetic energy", 0, 1},
      {"solver.newton.early_stop_window", T::Number, "0.1", "s", "early stop: time the threshold must hold", 0, 10},
      {"solver.cg.tolerance", T::Number, "1e-2", "", "PCG relative tolerance tau_cg", 1e-14, 0.9},
      {"solver.cg.max_iterations", T::Integer, "500", "", "PCG iteration cap", 1, 1e6},
      {"solver.cg.preconditioner", T::Choice, "block_jacobi", "", "PCG preconditioner", -1e300, 1e300,
       {"none", "diagonal", "block_jacobi", "incomplete_cholesky", "cholmod_direct"}},
      {"solver.cg.mixed_precision", T::Boolean, "false", "", "PCG in single precision (derivatives stay double)"},
      {"solver.cg.warm_start", T::Boolean, "true", "", "PCG starts from the last step's velocity change"},
      {"solver.cg.fused_kernels", T::Boolean, "true", "",
       "fused parallel block PCG (one pass per phase, deterministic TBB reductions); false: plain Eigen PCG"},
      {"solver.newton.reorder_dofs", T::Boolean, "true", "", "Reverse Cuthill-McKee order of the matrix rows (6.4)"},
      {"solver.newton.closed_form_bending", T::Boolean, "true", "",
       "closed-form hinge-angle gradient (false: automatic differentiation)"},
      {"solver.newton.block_map", T::Boolean, "true", "", "precomputed stencil -> matrix block map (6.1)"},
      {"solver.newton.parallel_assembly", T::Boolean, "true", "", "stencil colouring + TBB assembly (6.5)"},
      {"solver.damping.air", T::Number, "5", "1/s", "air drag alpha", 0, 1e3},
      {"solver.damping.stretch", T::Number, "1e-2", "s", "stretch dissipation beta_s", 0, 10},
      {"solver.damping.bend", T::Number, "1e-1", "s", "bending dissipation beta_b", 0, 10},
      {"solver.stitch_stiffness", T::Number, "1e4", "N/m", "zero-length stitch spring stiffness", 0, 1e9},
      {"solver.pin_stiffness", T::Number, "1e4", "N/m", "pin spring stiffness", 0, 1e9},
      // Contact
      {"contact.stiffness", T::Number, "100", "N/m", "penalty stiffness of avatar and cloth contact (paper: 1e2)", 0, 1e9},
      {"contact.thickness", T::Number, "", "m", "override: contact thickness (default: the fabric's thickness, at least 2 mm)", 0, 0.1},
      {"contact.friction", T::Boolean, "true", "", "Coulomb friction (off, or fabric friction 0: no friction term)"},
      {"contact.self_collision", T::Boolean, "false", "", "cloth-cloth contact (builds the self-collision BVH)"},
      {"camera.view", T::Choice, "three-quarter", "", "default camera preset", -1e300, 1e300,
       {"front", "back", "left", "right", "three-quarter"}},
      {"camera.fov_deg", T::Number, "35", "deg", "vertical field of view", 5, 120},
      {"camera.eye", T::Vector3, "", "m", "explicit camera position (overrides camera.view unless --view is given)"},
      {"camera.target", T::Vector3, "", "m", "point the explicit camera looks at (default: centre of the scene)"},
      {"camera.up", T::Vector3, "0,1,0", "", "up direction of the explicit camera"},
  };
  return table;
}

}  // namespace drape
