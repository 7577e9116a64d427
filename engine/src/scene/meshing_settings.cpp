#include "drape/scene/meshing_settings.h"

namespace drape {

MeshingOptions meshingOptions(const Scene& scene) {
  MeshingOptions o;
  o.targetEdgeLength = scene.settings.number("mesh.target_edge_length");
  o.conformingSeams = scene.settings.flag("mesh.conforming_seams");
  o.placementOffset = scene.settings.vector3("placement.translate");
  return o;
}

bool placementFit(const Scene& scene) {
  return scene.settings.flag("placement.fit");
}

}  // namespace drape
