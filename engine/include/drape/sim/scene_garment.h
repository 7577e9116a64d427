#pragma once
// The scene's garment: the pattern meshed as the scene's mesh.* settings ask and placed where its panels say, moved
// by placement.translate, then fitted to the scene's avatar (placement.fit; garment/placement_fit.h). Every place
// that meshes a scene's garment (Simulation, --info, --simulate and --render of the placed garment) builds it here,
// so that vertex counts and positions agree.
#include "drape/core/diagnostics.h"
#include "drape/garment/garment.h"
#include "drape/garment/garment_builder.h"
#include "drape/scene/meshing_settings.h"
#include "drape/scene/scene.h"

namespace drape {

// buildGarment with meshingOptions(scene). With an avatar and placement.fit on, fitPlacementToAvatar then moves the
// panels onto the avatar (clearance: the scene's contact thickness; a warning per panel moved far). It also warns
// (in diagnostics) when the garment's centre, after the fit, lies outside the avatar's bounding box: the pattern
// was laid out around another body or origin (the Garment-Pattern-Generator files put their bodies' origin at the
// hips), and placement.translate moves it.
Garment buildSceneGarment(const Scene& scene, Diagnostics* diagnostics);

}  // namespace drape
