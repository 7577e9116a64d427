#pragma once
// Synthetic snapshots for render tests and the render benchmark: analytic shapes with known layout, so a
// golden image depends on nothing but this file and the renderer.
#include "drape/sim/snapshot.h"

namespace drape::test {

// A square tablecloth (side metres, cells x cells quads) draped analytically over a sphere of radius 0.25 m
// centred 0.45 m above the floor: a cap lying on the sphere, then a skirt falling with radial folds.
// Two panels (x < 0 and x >= 0), strain from drape::triangleStretch against the flat rest grid, four
// domains by quadrant, contacts where the cloth lies on the sphere. The sphere is the avatar.
Snapshot tableclothScene(int cells = 32, double side = 1.0, int sphereSubdivisions = 3);

// A flared, folded skirt of two panels (front, back) hanging from the equator of a sphere "torso", open at
// both ends so its inside (back faces) shows from above. rings x segments quads; strain against an
// unrolled rest cylinder; six domains by angle; contacts along the top ring.
Snapshot skirtScene(int rings = 16, int segments = 48, int sphereSubdivisions = 3);

}  // namespace drape::test
