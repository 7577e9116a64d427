#pragma once
// Scene + garment -> the solvers' ClothModel. Private to the engine (and its benchmarks).
#include "drape/garment/garment.h"
#include "drape/model/cloth_model.h"
#include "drape/scene/scene.h"
#include "drape/scene/stage_settings.h"

namespace drape {

// The garment's cloth model: its fabrics per triangle, stitches, pins (moving pins follow their motion) and gravity
// (m/s^2 along y; the scene's own in the first form).
model::ClothModel buildClothModel(const Scene& scene, const Garment& garment, const std::vector<int>& pinned);
model::ClothModel buildClothModel(const Scene& scene, const Garment& garment, const std::vector<int>& pinned,
                                  double gravity);

}  // namespace drape
