#pragma once
// Fits a placed garment to the avatar it is draped on. A GarmentCode pattern places its panels around the body it
// was made for; on a body of other proportions a sleeve can start inside the shoulder or a hem inside the hips.
// The fit groups the panels by the body region they dress (by name: torso, sleeve -> left / right arm, hood ->
// head, skirt / pant / leg -> hips and legs; panels sewn together in one region move together), finds where each
// group sits (a torso by the top ends of its armholes or its top edge, a sleeve by its armhole's top point and its
// axis from armhole to cuff, a skirt by its waistband) and moves each group rigidly onto the avatar's landmarks
// (avatar/body_landmarks.h): a sleeve turns about its armhole to the arm's direction. Offsets within a tolerance
// (a pattern's own ease and the landmarks' uncertainty) are left alone, so a pattern that fits stays where it is.
// Then every panel with vertices inside the avatar moves outward, rigidly, until it is clear.
#include <string>
#include <vector>

#include "drape/core/diagnostics.h"
#include "drape/garment/garment.h"
#include "drape/geometry/triangle_mesh.h"
#include "drape/pattern/pattern.h"

namespace drape {

struct PlacementFitOptions {
  // Vertices closer to the avatar's surface than this (or inside it) count as intersecting, metres.
  double clearance = 3e-4;
  // A panel that moved farther than this gets a warning, metres.
  double warnDistance = 0.03;
};

struct PanelPlacementMove {
  std::string panel;
  double distance = 0.0;  // the largest move of one of its vertices, metres
};

struct PlacementFitResult {
  bool fitted = false;  // false when the avatar's landmarks were not found (the garment is left as it was)
  std::vector<PanelPlacementMove> moves;  // one per panel, in panel order
};

// Moves garment.positions (placed by buildGarment from pattern) onto avatar (metres, y up, feet at the bottom,
// facing +z). Warns in diagnostics, one line per panel naming pattern.source, when a panel moved farther than
// options.warnDistance, and once when the avatar's landmarks were not found.
PlacementFitResult fitPlacementToAvatar(const Pattern& pattern, Garment& garment, const TriangleMesh& avatar,
                                        const PlacementFitOptions& options = {}, Diagnostics* diagnostics = nullptr);

}  // namespace drape
