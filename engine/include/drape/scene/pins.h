#pragma once
// Turns the scene's pin specifications into garment vertex indices.
#include <vector>

#include "drape/garment/garment.h"
#include "drape/scene/scene.h"

namespace drape {

// Sorted, unique indices of pinned garment vertices. A pin that selects no vertex raises InputError naming it.
std::vector<int> resolvePins(const Scene& scene, const Garment& garment);

}  // namespace drape
