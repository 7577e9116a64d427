#pragma once
// Turns a Pattern into a Garment: samples every edge by arc length (stitched edges get the same number of
// points on both sides unless conformingSeams is off), meshes each panel at its target edge length, converts to
// metres and places the panels in 3D with their translation and XYZ Euler rotation.
#include <map>
#include <string>

#include "drape/core/diagnostics.h"
#include "drape/garment/garment.h"
#include "drape/pattern/pattern.h"

namespace drape {

struct MeshingOptions {
  double targetEdgeLength = 0.01;  // metres; edges get max(1, round(length / target)) segments
  // true: stitched edges share one segment count and pair vertex for vertex (Garment::stitchPairs); false: every
  // edge is sampled at its own spacing and each vertex of a seam's finer side is sewn to a point of the other
  // side's edge (Garment::edgeStitches; sides with equal counts still pair vertex for vertex).
  bool conformingSeams = true;
  // Per-panel target edge length, metres, by panel name (e.g. finer sleeves); panels not listed use
  // targetEdgeLength. With conforming seams the stitched edges still share the larger of their counts.
  std::map<std::string, double> panelTargetEdgeLength;
  // Added to every placed position, metres (the scene's placement.translate).
  Eigen::Vector3d placementOffset = Eigen::Vector3d::Zero();
};

// Throws InputError naming the pattern file and panel/stitch for: a non-positive target or units_in_meter, a
// per-panel target that is not positive or names no panel, a stitch naming a missing panel or edge, an outline
// that is not closed, cannot be meshed (see meshPanel) or would exceed the triangle limit. Warns in diagnostics about edges used by more than one stitch.

Garment buildGarment(const Pattern& pattern, const MeshingOptions& options, Diagnostics* diagnostics = nullptr);

// The 3D placement of a panel's 2D point (file units in, metres out): (R * [x, y, 0] + translation) / unitsInMeter
// with R = Rx * Ry * Rz (intrinsic XYZ Euler angles, as GarmentCode writes them with scipy's as_euler('XYZ')).
// The shared data files cannot tell this from Rz * Ry * Rx (they rotate about z only, or by 180 degrees
// about two axes, which commute).
Eigen::Vector3d placePanelPoint(const Panel& panel, const Eigen::Vector2d& p, double unitsInMeter);

}  // namespace drape
