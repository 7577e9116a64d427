#pragma once
// The thresholds of the quality verdict (sim/drape_quality.h), read once from the scene's quality.* settings.
namespace drape {

class Settings;

// Thresholds of the checks (settings quality.*).
struct QualitySettings {
  double maxStrain = 1.0;             // largest triangle stretch (0.05 = 5 %)
  double maxInsideFraction = 0.01;    // fraction of garment vertices inside a collider
  double maxPenetrationDepth = 0.0;   // metres; 0: the contact thickness
  double nearSkinDistance = 1e-3;     // metres: a vertex nearer to a collider's surface than this (or inside) is near
  double maxNearSkinFraction = 0.01;  // fraction of garment vertices near or inside a collider
  int maxSelfIntersections = 0;       // pairs of garment triangles that cross
  double maxSeamGap = 0.003;          // metres: largest distance between two sewn points of a seam
  // Smallest fraction of the garment faces resting near a collider (centroid within kOutwardNearDistance) whose
  // normal points away from it: a panel wound into the body renders in the inside colour and exports inside out.
  // Folds and crumples lying on the body turn a few faces over legitimately.
  double minOutwardFraction = 0.98;
  bool requireRest = true;  // the run must end at rest (end status "AtRest")
};
QualitySettings qualitySettingsFrom(const Settings& settings);

}  // namespace drape
