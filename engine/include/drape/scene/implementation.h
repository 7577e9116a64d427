#pragma once
// Switches between implementations of one computation that give the same drape (to round-off, or to the solver's
// own tolerance): a scene file cannot set them. The benchmarks that measure what each implementation costs
// (bench/newton_bench, the domain-decomposed solve against monolithic CHOLMOD) and the tests that compare them set
// them on Scene::implementation. Every default is the fastest implementation.
namespace drape {

struct Implementation {
  // Newton drape (newton-drape-pizana section 6)
  bool closedFormBending = true;  // closed-form hinge-angle gradient (false: automatic differentiation)
  bool blockMap = true;           // precomputed stencil -> matrix block map (6.1)
  bool parallelAssembly = true;   // stencil colouring + TBB assembly (6.5)
  bool foldDissipation = true;    // membrane and bending add their dissipations before one scatter per stencil
  bool batchedGradients = true;   // membrane and bending gradient passes take 8 stencils at a time
  bool reorderDofs = true;        // Reverse Cuthill-McKee order of the matrix rows (6.4)
  bool fusedKernels = true;       // fused parallel block PCG (false: Eigen's PCG, without the two-level parts)
  // Preview (pd-dd-lu2025 section 4): the global solve by one monolithic CHOLMOD factor instead of the domains.
  bool monolithicGlobalSolve = false;
};

}  // namespace drape
