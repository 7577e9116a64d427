#pragma once
// Turns a Pattern into a Garment: samples every edge by arc length (stitched edges get the same number of
// points on both sides), meshes each panel at the target edge length, converts to metres and places the
// panels in 3D with their translation and XYZ Euler rotation.
#include "drape/core/diagnostics.h"
#include "drape/garment/garment.h"
#include "drape/pattern/pattern.h"

namespace drape {

struct MeshingOptions {
  double targetEdgeLength = 0.01;  // metres; edges get max(1, round(length / target)) segments
};

// Throws InputError naming the pattern file and panel/stitch for: a non-positive target or units_in_meter, a
// stitch naming a missing panel or edge, an outline that is not closed, cannot be meshed (see meshPanel) or
// would exceed the triangle limit. Warns in diagnostics about edges used by more than one stitch.

Garment buildGarment(const Pattern& pattern, const MeshingOptions& options, Diagnostics* diagnostics = nullptr);

// The 3D placement of a panel's 2D point (file units in, metres out): (R * [x, y, 0] + translation) / unitsInMeter
// with R = Rx * Ry * Rz (intrinsic XYZ Euler angles, as GarmentCode writes them with scipy's as_euler('XYZ')).
// The shared data files cannot tell this from Rz * Ry * Rx (they rotate about z only, or by 180 degrees
// about two axes, which commute).
Eigen::Vector3d placePanelPoint(const Panel& panel, const Eigen::Vector2d& p, double unitsInMeter);

}  // namespace drape
