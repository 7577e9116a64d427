#include "drape/collision/contact_merged_vertices.h"

namespace drape::collision {

std::vector<std::pair<int, int>> contactMergedVertices(const std::vector<std::pair<int, int>>& stitchPairs,
                                                       const std::vector<model::EdgeStitch>& edgeStitches) {
  std::vector<std::pair<int, int>> merged = stitchPairs;
  merged.reserve(stitchPairs.size() + edgeStitches.size());
  for (const model::EdgeStitch& e : edgeStitches) merged.emplace_back(e.vertex, e.t <= 0.5 ? e.a : e.b);
  return merged;
}

}  // namespace drape::collision
