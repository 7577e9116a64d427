#pragma once
// Linear bounding volume hierarchy over axis-aligned boxes (Karras 2012, "Maximizing parallelism in the
// construction of BVHs, octrees and k-d trees"; pd-dd section 7.3 broad phase). Built from 63-bit Morton codes
// of the box centres and a binary radix tree; refit keeps the tree and recomputes the boxes bottom-up, as is
// done every time step while the topology stays fixed.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "drape/collision/aabb.h"
#include "drape/geometry/triangle_mesh.h"

namespace drape::collision {

class Bvh {
 public:
  Bvh() = default;
  explicit Bvh(const std::vector<BoundingBox>& boxes) { build(boxes); }

  // Builds the tree over boxes (one per primitive; primitive id = index). Any count, 0 included.
  void build(const std::vector<BoundingBox>& boxes);
  // Recomputes every node box from new primitive boxes; boxes.size() must equal primitiveCount().
  void refit(const std::vector<BoundingBox>& boxes);

  int primitiveCount() const { return m_count; }
  bool empty() const { return m_count == 0; }
  // Box of everything (empty box when there are no primitives).
  BoundingBox bounds() const { return m_count == 0 ? BoundingBox{} : m_nodes[0].box; }
  // Longest root-to-leaf path (number of edges), for tests and statistics.
  int depth() const;

  // Calls visit(primitive) for every primitive whose box overlaps `box`.
  template <class Visit>
  void forEachOverlap(const BoundingBox& box, Visit&& visit) const {
    forEachOverlapAfter(box, -1, visit);
  }

  // Self-overlap in pairs: primitiveAt(k) is the primitive of leaf k (leaves in Morton order), and
  // forEachOverlapAfter(box, k, visit) calls visit only for the primitives of leaves after k. Querying every
  // primitive's own box after its own leaf finds each overlapping pair once and skips the subtrees of the leaves before.
  int primitiveAt(int leaf) const { return m_leafPrimitive[leaf]; }
  template <class Visit>
  void forEachOverlapAfter(const BoundingBox& box, int leaf, Visit&& visit) const;

  // Branch-and-bound nearest primitive to p. primDistance2(primitive) returns the exact squared distance of the
  // primitive to p. On entry bestDistance2 is an upper bound (infinity for none); on return it is the smallest
  // distance found below it, and the result is the primitive reaching it (-1 when none beat the bound).
  template <class Distance2>
  int nearest(const Eigen::Vector3d& p, Distance2&& primDistance2, double& bestDistance2) const;

 private:
  struct Node {
    BoundingBox box;
    int left = -1;   // child node indices; internal nodes are [0, n-1), leaves [n-1, 2n-1)
    int right = -1;
    int last = 0;  // the last leaf position under the node
  };
  bool isLeaf(int node) const { return node >= m_count - 1; }
  int leafPrimitive(int node) const { return m_leafPrimitive[node - (m_count - 1)]; }

  int m_count = 0;
  std::vector<Node> m_nodes;
  std::vector<int> m_leafPrimitive;  // leaf k -> primitive id (sorted by Morton code)
  std::vector<int> m_refitOrder;     // internal nodes, children before parents
};

template <class Visit>
void Bvh::forEachOverlapAfter(const BoundingBox& box, int leaf, Visit&& visit) const {
  if (m_count == 0 || m_nodes[0].last <= leaf || !overlaps(m_nodes[0].box, box)) return;
  std::array<int, 128> stack;
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int node = stack[--top];
    if (isLeaf(node)) {
      visit(leafPrimitive(node));
      continue;
    }
    const Node& n = m_nodes[node];
    if (m_nodes[n.left].last > leaf && overlaps(m_nodes[n.left].box, box)) stack[top++] = n.left;
    if (m_nodes[n.right].last > leaf && overlaps(m_nodes[n.right].box, box)) stack[top++] = n.right;
  }
}

template <class Distance2>
int Bvh::nearest(const Eigen::Vector3d& p, Distance2&& primDistance2, double& bestDistance2) const {
  int best = -1;
  if (m_count == 0 || squaredDistance(m_nodes[0].box, p) >= bestDistance2) return best;
  std::array<std::pair<int, double>, 128> stack;
  int top = 0;
  stack[top++] = {0, 0.0};
  while (top > 0) {
    const auto [node, boxDistance2] = stack[--top];
    if (boxDistance2 >= bestDistance2) continue;
    if (isLeaf(node)) {
      const int prim = leafPrimitive(node);
      const double d2 = primDistance2(prim);
      if (d2 < bestDistance2) {
        bestDistance2 = d2;
        best = prim;
      }
      continue;
    }
    const Node& n = m_nodes[node];
    double dl = squaredDistance(m_nodes[n.left].box, p);
    double dr = squaredDistance(m_nodes[n.right].box, p);
    int first = n.left;
    int second = n.right;
    if (dr < dl) {
      std::swap(first, second);
      std::swap(dl, dr);
    }
    // Push the farther child first so the nearer one is explored first.
    if (dr < bestDistance2) stack[top++] = {second, dr};
    if (dl < bestDistance2) stack[top++] = {first, dl};
  }
  return best;
}

}  // namespace drape::collision
