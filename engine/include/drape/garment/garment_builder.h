#pragma once
// Turns a Pattern into a Garment: samples every edge by arc length (stitched edges get the same number of
// points on both sides), meshes each panel at the target edge length, converts to metres and places the
// panels in 3D with their translation and XYZ Euler rotation.
#include "drape/core/diagnostics.h"
#include "drape/garment/garment.h"
#include "drape/pattern/pattern.h"

namespace drape {

struct MeshingOptions {
  double targetEdgeLength = 0.01;  // metres
};

Garment buildGarment(const Pattern& pattern, const MeshingOptions& options, Diagnostics* diagnostics = nullptr);

// The 3D placement of a panel's 2D point (file units in, metres out): R(rotation) * [x, y, 0] + translation.
Eigen::Vector3d placePanelPoint(const Panel& panel, const Eigen::Vector2d& p, double unitsInMeter);

}  // namespace drape
