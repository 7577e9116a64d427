// Degree-of-freedom reordering of the Newton drape solver (newton-drape-pizana section 6.4): the static stencil
// graph (vertices = nodes, coupled vertex pairs = edges) is renumbered by Reverse Cuthill-McKee so that the
// block matrix has a small bandwidth and its SpMV and block-Jacobi sweeps read memory close together.
#pragma once

#include <utility>
#include <vector>

namespace drape::newton {

// Undirected graph on numNodes nodes given by its edges (pairs may repeat, come in either order; self loops are
// ignored) as sorted, duplicate-free adjacency lists.
std::vector<std::vector<int>> adjacencyLists(int numNodes, const std::vector<std::pair<int, int>>& edges);

// Reverse Cuthill-McKee ordering: order[k] = the node placed at position k. Every connected component is
// numbered from a pseudo-peripheral start node (George-Liu search), neighbours visited by increasing degree,
// and the whole sequence reversed. The result is a permutation of 0 .. numNodes-1.
std::vector<int> reverseCuthillMcKee(const std::vector<std::vector<int>>& adjacency);

// Inverse of a permutation: inverse[order[k]] = k.
std::vector<int> invertPermutation(const std::vector<int>& order);

// Bandwidth max |position(i) - position(j)| over the edges, for the numbering position (identity when empty).
int graphBandwidth(const std::vector<std::vector<int>>& adjacency, const std::vector<int>& position = {});

}  // namespace drape::newton
