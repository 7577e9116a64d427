#pragma once
// A smooth, watertight mannequin made from body measurements: an original parametric implicit body (analytic
// horizontal sections whose sizes follow the measurements, fitted exactly to the measured girths, a head, feet
// and tapered limbs, smoothly blended) meshed with CGAL's surface mesher. See docs/MANNEQUIN.md.
#include "drape/avatar/body_measurements.h"
#include "drape/geometry/triangle_mesh.h"

namespace drape {

struct MannequinOptions {
  double facetSize = 0.010;      // metres: upper bound on the surface Delaunay ball radius of a facet
  double facetDistance = 0.002;  // metres: upper bound on the distance from a facet to the implicit surface
  double facetAngle = 25.0;      // degrees: lower bound on the smallest facet angle
};

// Heights above the floor (metres) of the mannequin's landmarks; the girths are fitted at these levels.
struct MannequinLevels {
  double crotch = 0.0;     // thighs are fitted to `thigh` here (each leg on its own)
  double hips = 0.0;       // waist - hips_line
  double waist = 0.0;      // neck base - waist_line
  double underbust = 0.0;  // 45% of the way from the bust level down to the waist level
  double bust = 0.0;       // neck base - vert_bust_line
  double neckBase = 0.0;   // height - head_l
  double top = 0.0;        // height
};

// Landmark heights of the mannequin for these measurements. Raises InputError when the landmarks are not
// in order from the floor up (e.g. a waist_line longer than the torso).
MannequinLevels mannequinLevels(const BodyMeasurements& measurements);

// The mannequin in metres: y up, feet at y = 0, facing +z, arms in the x-y plane at arm_pose_angle below the
// horizontal. A closed manifold with counter-clockwise outward triangles (about 20k-60k with the default
// options). Raises InputError for inconsistent measurements.
TriangleMesh makeMannequin(const BodyMeasurements& measurements, const MannequinOptions& options = {});

}  // namespace drape
