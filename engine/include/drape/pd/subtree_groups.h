#pragma once
// Groups of independent subtrees of an elimination tree, for a triangular solve on several threads: the nodes of
// each group depend only on nodes of the same group, so the groups run side by side; the nodes above them (the
// separators, "top") run afterwards on one thread (forward substitution; the reverse for backward substitution).
#include <vector>

namespace drape::pd {

struct SubtreeGroups {
  std::vector<std::vector<int>> groups;  // nodes of each group, ascending; empty: nothing to split
  std::vector<int> top;                  // the nodes above the groups, ascending
  long cost = 0;                         // work of top + the largest group; the total work when not split
};

// parent[j] > j, or -1 for a root; cost[j] >= 0: the work of node j. Subtree roots move to the top one by one,
// the costliest first, and the number of moves with the smallest top + largest group (groups filled by
// longest-processing-time assignment) is kept. groupCount < 2 or a single chain: no groups.
SubtreeGroups groupSubtrees(const std::vector<int>& parent, const std::vector<long>& cost, int groupCount);

}  // namespace drape::pd
