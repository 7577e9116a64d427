#pragma once
// Scene + garment -> the solvers' ClothModel and settings. Private to the engine (and its benchmarks).
#include "drape/garment/garment.h"
#include "drape/model/cloth_model.h"
#include "drape/newton/newton_solver.h"
#include "drape/pd/preview_settings.h"
#include "drape/scene/scene.h"

namespace drape {

model::ClothModel buildClothModel(const Scene& scene, const Garment& garment, const std::vector<int>& pinned);

// The drape's settings from the scene's solver.* keys, its stretch dissipation beta_s from the fabric's damping.
newton::NewtonSettings newtonSettingsFrom(const Scene& scene);

// The preview solver's settings from the scene's solver.preview.* keys (friction: the largest coefficient of the
// scene's fabrics, as the drape).
pd::PreviewSettings previewSettingsFrom(const Scene& scene);

// Contact thickness of the scene: contact.thickness if set, else the thickest fabric's thickness, at least 2 mm.
double contactThickness(const Scene& scene);

}  // namespace drape
