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
// A vertex pin with saved positions (PinSpec::at) selects, per entry, the vertex at its saved position: the index
// given when that vertex lies within 1 um of it, else the vertex nearest to it (the index was stale: the mesh was
// renumbered), one entry per entry of PinSpec::vertices. When the nearest vertex is farther than
// vertexPinTolerance(scene), throws InputError naming the pin, the entry, the position and the distance.
std::vector<int> pinVertices(const PinSpec& pin, const Scene& scene, const Garment& garment);

// How far (metres) a vertex pin's saved position may lie from the vertex it selects: a quarter of
// mesh.target_edge_length, at most 5 mm. The same pattern and mesh settings place vertices identically (to
// round-off), so a larger distance means the pattern, its placement or its meshing changed.
double vertexPinTolerance(const Scene& scene);

// For every vertex of pinned (as resolvePins returns them): the index in scene.pins of the last moving pin that
// selects it, or -1 when no moving pin does.
std::vector<int> pinMotionIndex(const Scene& scene, const Garment& garment, const std::vector<int>& pinned);

}  // namespace drape
