#include "drape/newton/dof_ordering.h"

#include <algorithm>
#include <cassert>
#include <cstdlib>

namespace drape::newton {
namespace {

// Breadth-first level structure from start within its component: fills level (-1 = unvisited before the call)
// and returns the nodes in visiting order; depth receives the number of levels.
std::vector<int> levelStructure(const std::vector<std::vector<int>>& adj, int start, std::vector<int>& level,
                                int& depth) {
  std::vector<int> visited{start};
  level[start] = 0;
  for (size_t head = 0; head < visited.size(); ++head) {
    const int u = visited[head];
    for (int w : adj[u])
      if (level[w] < 0) {
        level[w] = level[u] + 1;
        visited.push_back(w);
      }
  }
  depth = level[visited.back()] + 1;
  return visited;
}

// George-Liu pseudo-peripheral node of start's component: repeatedly jump to a minimum-degree node of the last
// BFS level while the number of levels grows.
int pseudoPeripheralNode(const std::vector<std::vector<int>>& adj, int start) {
  std::vector<int> level(adj.size(), -1);
  int depth = 0;
  std::vector<int> comp = levelStructure(adj, start, level, depth);
  int node = start;
  for (int round = 0; round < 16; ++round) {
    int best = -1;
    for (int u : comp)
      if (level[u] == depth - 1 && (best < 0 || adj[u].size() < adj[best].size())) best = u;
    for (int u : comp) level[u] = -1;
    int newDepth = 0;
    comp = levelStructure(adj, best, level, newDepth);
    if (newDepth <= depth) break;
    depth = newDepth;
    node = best;
  }
  return node;
}

}  // namespace

std::vector<std::vector<int>> adjacencyLists(int numNodes, const std::vector<std::pair<int, int>>& edges) {
  std::vector<std::vector<int>> adj(numNodes);
  for (const auto& [a, b] : edges) {
    assert(a >= 0 && a < numNodes && b >= 0 && b < numNodes);
    if (a == b) continue;
    adj[a].push_back(b);
    adj[b].push_back(a);
  }
  for (auto& row : adj) {
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
  }
  return adj;
}

std::vector<int> reverseCuthillMcKee(const std::vector<std::vector<int>>& adj) {
  const int n = static_cast<int>(adj.size());
  std::vector<int> order;
  order.reserve(n);
  std::vector<char> placed(n, 0);
  std::vector<int> neighbours;
  for (int seed = 0; seed < n; ++seed) {
    if (placed[seed]) continue;
    const int start = pseudoPeripheralNode(adj, seed);
    size_t head = order.size();
    order.push_back(start);
    placed[start] = 1;
    // Cuthill-McKee: breadth first, unplaced neighbours of each node appended by increasing degree.
    for (; head < order.size(); ++head) {
      neighbours.clear();
      for (int w : adj[order[head]])
        if (!placed[w]) neighbours.push_back(w);
      std::stable_sort(neighbours.begin(), neighbours.end(),
                       [&adj](int a, int b) { return adj[a].size() < adj[b].size(); });
      for (int w : neighbours) {
        placed[w] = 1;
        order.push_back(w);
      }
    }
  }
  std::reverse(order.begin(), order.end());
  return order;
}

std::vector<int> invertPermutation(const std::vector<int>& order) {
  std::vector<int> inverse(order.size(), -1);
  for (size_t k = 0; k < order.size(); ++k) inverse[order[k]] = static_cast<int>(k);
  return inverse;
}

int graphBandwidth(const std::vector<std::vector<int>>& adj, const std::vector<int>& position) {
  int bw = 0;
  for (int i = 0; i < static_cast<int>(adj.size()); ++i) {
    const int pi = position.empty() ? i : position[i];
    for (int j : adj[i]) bw = std::max(bw, std::abs(pi - (position.empty() ? j : position[j])));
  }
  return bw;
}

}  // namespace drape::newton
