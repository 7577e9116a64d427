#pragma once
// Scene + garment -> the Newton solver's ClothModel and settings. Private to the engine.
#include "drape/garment/garment.h"
#include "drape/newton/cloth_model.h"
#include "drape/newton/newton_solver.h"
#include "drape/scene/scene.h"

namespace drape {

newton::ClothModel buildClothModel(const Scene& scene, const Garment& garment, const std::vector<int>& pinned);

newton::NewtonSettings newtonSettingsFrom(const Settings& settings);

// Contact thickness of the scene: contact.thickness if set, else the thickest fabric's thickness, at least 2 mm.
double contactThickness(const Scene& scene);

}  // namespace drape
