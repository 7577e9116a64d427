#pragma once
// Cloth self-proximity broad + narrow phase: every vertex-triangle and edge-edge pair of one cloth mesh closer
// than a distance, excluding pairs that share a vertex (newton-drape-pizana 3.3: BVH proximity queries among
// cloth objects). Two LBVHs (triangles, edges) are refitted to the current positions on every query.
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "drape/collision/bvh.h"

namespace drape::collision {

struct VertexTrianglePair {
  int vertex = 0;
  int triangle = 0;
  friend bool operator==(const VertexTrianglePair&, const VertexTrianglePair&) = default;
  friend auto operator<=>(const VertexTrianglePair&, const VertexTrianglePair&) = default;
};

struct EdgeEdgePair {
  int first = 0;   // index into SelfProximity::edges(), first < second
  int second = 0;
  friend bool operator==(const EdgeEdgePair&, const EdgeEdgePair&) = default;
  friend auto operator<=>(const EdgeEdgePair&, const EdgeEdgePair&) = default;
};

// Undirected edges of a triangle mesh, each (i, j) with i < j, sorted, without repeats: |E| x 2.
Eigen::MatrixX2i uniqueEdges(const Eigen::MatrixX3i& triangles);

class SelfProximity {
 public:
  // triangles: |F| x 3 indices into vertexCount vertices. mergedVertices: vertex pairs that count as one vertex
  // for adjacency (stitched seam vertices, which meet when the seam closes and must not repel each other).
  SelfProximity(const Eigen::MatrixX3i& triangles, int vertexCount,
                const std::vector<std::pair<int, int>>& mergedVertices = {});

  // All non-adjacent vertex-triangle and edge-edge pairs at distance < d (metres, d > 0) for positions x
  // (flat, size 3|V|). Refits the trees to x first (rebuilding them every `rebuildInterval` calls, since a
  // refitted tree degrades as the cloth moves far from where it was built). Output sorted; parallel (TBB).
  void findPairs(const Eigen::VectorXd& x, double d, std::vector<VertexTrianglePair>& vertexTriangle,
                 std::vector<EdgeEdgePair>& edgeEdge);

  // True when the pair shares a vertex (after merging) and is never reported.
  bool adjacent(const VertexTrianglePair& p) const;
  bool adjacent(const EdgeEdgePair& p) const;

  const Eigen::MatrixX3i& triangles() const { return m_triangles; }
  const Eigen::MatrixX2i& edges() const { return m_edges; }
  int vertexCount() const { return m_vertexCount; }
  // Representative of v's merged group (v itself when not merged).
  int canonical(int v) const { return m_canonical[v]; }

  int rebuildInterval = 64;  // refits between full rebuilds

 private:
  void updateTrees(const Eigen::VectorXd& x);

  Eigen::MatrixX3i m_triangles;
  Eigen::MatrixX2i m_edges;
  int m_vertexCount = 0;
  std::vector<int> m_canonical;
  Bvh m_triangleTree;
  Bvh m_edgeTree;
  int m_refitsSinceBuild = -1;  // -1: not built yet
  std::vector<BoundingBox> m_boxes;
};

}  // namespace drape::collision
