#pragma once
// How a scene's garment is meshed and placed, read once from its mesh.* and placement.* settings.
#include "drape/garment/garment_builder.h"
#include "drape/scene/scene.h"

namespace drape {

// Target edge length, conforming seams and the placement offset from the scene's settings.
MeshingOptions meshingOptions(const Scene& scene);

// placement.fit: the panels are fitted onto the scene's avatar (garment/placement_fit.h).
bool placementFit(const Scene& scene);

}  // namespace drape
