#pragma once
// Disjoint sets as a parent array (parent[i] == i at a root): the root of i's set, halving the path on the way.
#include <vector>

namespace drape {

inline int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace drape
