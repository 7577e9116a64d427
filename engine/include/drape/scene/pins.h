#pragma once
// Turns the scene's pin specifications into garment vertex indices.
#include <vector>

#include "drape/garment/garment.h"
#include "drape/scene/scene.h"

namespace drape {

// Sorted, unique indices of pinned garment vertices. A pin that selects no vertex, or a vertex index outside the
// garment, raises InputError naming it.
std::vector<int> resolvePins(const Scene& scene, const Garment& garment);

// Garment vertices one pin selects (unsorted; empty when it selects none). Throws InputError for a vertex index
// outside the garment.
std::vector<int> pinVertices(const PinSpec& pin, const Scene& scene, const Garment& garment);

// For every vertex of pinned (as resolvePins returns them): the index in scene.pins of the last moving pin that
// selects it, or -1 when no moving pin does.
std::vector<int> pinMotionIndex(const Scene& scene, const Garment& garment, const std::vector<int>& pinned);

}  // namespace drape
