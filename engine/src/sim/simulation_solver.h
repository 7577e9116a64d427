#pragma once
// The solvers a Simulation owns (simulation.h), shared by its source files. Private to the engine.
#include <Eigen/SparseCore>
#include <memory>

#include "drape/collision/avatar_collider.h"
#include "drape/model/cloth_model.h"
#include "drape/newton/newton_solver.h"
#include "drape/pd/pd_preconditioner.h"
#include "drape/pd/preview_solver.h"
#include "drape/sim/simulation.h"
#include "sim/contact_terms.h"

namespace drape {

struct Simulation::Solver {
  model::ClothModel model;
  std::shared_ptr<const collision::AvatarCollider> collider;
  std::unique_ptr<pd::PreviewSolver> preview;  // while the stage is "preview"
  std::unique_ptr<newton::NewtonSolver> newton;  // once the stage is "drape", and for the quasi-Newton preview
  // solver.preview.method quasi_newton: `newton` solves the drape's model by L-BFGS preconditioned by this until the
  // hand-over (quasiNewtonPreview true), then by Newton.
  std::shared_ptr<pd::PdPreconditioner> preconditioner;
  bool quasiNewtonPreview = false;
  double newtonOffset = 0.0;                     // scene time at the Newton solver's time 0, s
  ContactTerms contact;                          // the drape's contact terms (energies moved into newton)
  Eigen::VectorXd masses;                        // |V| lumped, kg
  double previewOffset = 0.0;                    // scene time at the preview solver's time 0, s
  double previewTime = 0.0;                      // scene time at which the drape started, s
  Eigen::MatrixX3d previewPositions;             // the state the drape started from; no rows = placed garment
  // solver.preview.assembly_edge_length: the preview sewing a coarser meshing of the same pattern, before
  // `preview` takes over on the garment's own mesh. Its state reaches the garment through toGarment.
  struct Assembly {
    Garment garment;
    std::unique_ptr<pd::PreviewSolver> preview;
    Eigen::SparseMatrix<double, Eigen::RowMajor> toGarment;  // |V| x |V_assembly|
    Eigen::VectorXd masses;                                  // |V_assembly| lumped, kg
  };
  std::unique_ptr<Assembly> assembly;
};

}  // namespace drape
