#pragma once
// Which garment vertices count as one in cloth-cloth contact, from the garment's seams (topology only; both the
// preview's cloth collision and the drape's self contact take these pairs).
#include <utility>
#include <vector>

#include "drape/model/cloth_model.h"

namespace drape::collision {

// Vertex pairs that count as one vertex in cloth-cloth contact (a closed seam must not repel itself): the
// vertex-to-vertex stitch pairs as given, then for every edge stitch (vertex sewn to (1 - t) x_a + t x_b of a
// non-conforming seam) the vertex with the nearer endpoint of its edge (a when t <= 1/2, else b). The nearer
// endpoint already excludes every triangle of the edge (each holds both endpoints). Not both endpoints: merged
// vertices form groups (union-find), and consecutive stitches on one edge would chain every vertex of the seam
// into one group, so a seam folded onto itself would never collide. With the nearer endpoint each coarse-side
// vertex gathers the fine-side vertices within half an edge of it, and groups never chain along the seam.
std::vector<std::pair<int, int>> contactMergedVertices(const std::vector<std::pair<int, int>>& stitchPairs,
                                                       const std::vector<model::EdgeStitch>& edgeStitches);

}  // namespace drape::collision
