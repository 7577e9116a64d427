#include "drape/sim/scene_garment.h"

#include <sstream>

#include "drape/scene/stage_settings.h"
#include "drape/garment/placement_fit.h"

namespace drape {
namespace {

std::string formatPoint(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s.precision(3);
  s << std::fixed << p.x() << ", " << p.y() << ", " << p.z();
  return s.str();
}

}  // namespace

Garment buildSceneGarment(const Scene& scene, Diagnostics* diagnostics) {
  Garment garment = buildGarment(scene.pattern, meshingOptions(scene), diagnostics);
  if (scene.hasAvatar() && placementFit(scene))
    fitPlacementToAvatar(scene.pattern, garment, scene.avatar, {contactThickness(scene)}, diagnostics);
  if (!diagnostics || !scene.hasAvatar() || garment.vertexCount() == 0) return garment;
  const BoundingBox body = boundsOf(scene.avatar.vertices);
  const Eigen::Vector3d centre = boundsOf(garment.positions).center();
  const bool inside = (centre.array() >= body.min.array()).all() && (centre.array() <= body.max.array()).all();
  if (!inside)
    diagnostics->warn(scene.patternFile.string() + ": the placed garment's centre (" + formatPoint(centre) +
                      " m) lies outside the avatar's bounding box (" + formatPoint(body.min) + " to " +
                      formatPoint(body.max) +
                      " m): the pattern was laid out around another body or origin; move it onto the avatar with "
                      "placement.translate (docs/FORMATS.md)");
  return garment;
}

}  // namespace drape
