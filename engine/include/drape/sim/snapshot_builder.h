#pragma once
// Builds a Snapshot of a garment in a given state, for rendering and export without a solver.
#include "drape/garment/garment.h"
#include "drape/scene/scene.h"
#include "drape/sim/snapshot.h"

namespace drape {

// positions: |V| x 3, metres. Strain is computed against the garment's rest shape; colliders are merged.
Snapshot makeSnapshot(const Scene& scene, const Garment& garment, const Eigen::MatrixX3d& positions);

// The scene's avatar and generated colliders as one mesh, metres.
TriangleMesh mergedColliders(const Scene& scene);

}  // namespace drape
