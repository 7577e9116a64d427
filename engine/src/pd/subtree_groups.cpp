#include "drape/pd/subtree_groups.h"

#include <algorithm>

namespace drape::pd {
namespace {

// Longest-processing-time assignment of subtrees (by cost, sorted here descending) to `groups` groups; returns
// the largest group's cost and, when asked, each subtree root's group.
long assignSubtrees(std::vector<int>& roots, const std::vector<long>& subtreeCost, int groups,
                    std::vector<int>* groupOf) {
  std::sort(roots.begin(), roots.end(), [&](int a, int b) { return subtreeCost[a] > subtreeCost[b]; });
  std::vector<long> load(groups, 0);
  for (int r : roots) {
    const int g = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    load[g] += subtreeCost[r];
    if (groupOf) (*groupOf)[r] = g;
  }
  return *std::max_element(load.begin(), load.end());
}

}  // namespace

SubtreeGroups groupSubtrees(const std::vector<int>& parent, const std::vector<long>& cost, int groupCount) {
  const int n = static_cast<int>(parent.size());
  SubtreeGroups plan;
  std::vector<long> subtreeCost(cost.begin(), cost.end());
  std::vector<std::vector<int>> children(n);
  std::vector<int> frontier;
  for (int j = 0; j < n; ++j) {  // parents come after their children
    if (parent[j] >= 0) {
      subtreeCost[parent[j]] += subtreeCost[j];
      children[parent[j]].push_back(j);
    } else {
      frontier.push_back(j);
      plan.cost += subtreeCost[j];
    }
  }
  if (groupCount < 2 || n < 2) return plan;
  // Move the costliest subtree's root to the top, again and again (a chain of single children has to be passed
  // before a split appears); remember after how many moves top + largest group was smallest.
  const std::vector<int> roots = frontier;
  std::vector<int> moved;
  long best = assignSubtrees(frontier, subtreeCost, groupCount, nullptr), topCost = 0;
  size_t bestMoves = 0;
  while (frontier.size() < 64u * static_cast<size_t>(groupCount)) {
    const int r = frontier.front();  // sorted by cost, descending
    if (children[r].empty()) break;
    frontier.erase(frontier.begin());
    frontier.insert(frontier.end(), children[r].begin(), children[r].end());
    moved.push_back(r);
    topCost += cost[r];
    const long total = topCost + assignSubtrees(frontier, subtreeCost, groupCount, nullptr);
    if (total < best) {
      best = total;
      bestMoves = moved.size();
    }
  }
  std::vector<char> top(n, 0);
  frontier = roots;
  for (size_t k = 0; k < bestMoves; ++k) {
    const int r = moved[k];
    top[r] = 1;
    frontier.erase(std::find(frontier.begin(), frontier.end(), r));
    frontier.insert(frontier.end(), children[r].begin(), children[r].end());
  }
  if (frontier.size() < 2) return plan;  // one chain: nothing to run side by side
  plan.cost = best;
  std::vector<int> groupOf(n, -1);
  assignSubtrees(frontier, subtreeCost, groupCount, &groupOf);
  for (int j = n - 1; j >= 0; --j)  // a subtree's nodes take its root's group (parents are visited first)
    if (!top[j] && groupOf[j] < 0) groupOf[j] = groupOf[parent[j]];
  plan.groups.assign(groupCount, {});
  for (int j = 0; j < n; ++j) (top[j] ? plan.top : plan.groups[groupOf[j]]).push_back(j);
  return plan;
}

}  // namespace drape::pd
