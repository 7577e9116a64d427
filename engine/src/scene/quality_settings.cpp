#include "drape/scene/quality_settings.h"

#include "drape/scene/settings.h"

namespace drape {

QualitySettings qualitySettingsFrom(const Settings& settings) {
  QualitySettings s;
  s.maxStrain = settings.number("quality.max_strain");
  s.maxInsideFraction = settings.number("quality.max_inside_fraction");
  s.maxPenetrationDepth = settings.number("quality.max_penetration_depth");
  s.nearSkinDistance = settings.number("quality.near_skin_distance");
  s.maxNearSkinFraction = settings.number("quality.max_near_skin_fraction");
  s.maxSelfIntersections = settings.integer("quality.max_self_intersections");
  s.maxSeamGap = settings.number("quality.max_seam_gap");
  s.minOutwardFraction = settings.number("quality.min_outward_fraction");
  s.requireRest = settings.flag("quality.require_rest");
  return s;
}

}  // namespace drape
