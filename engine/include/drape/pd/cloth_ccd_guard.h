#pragma once
// End-of-step safety net of the PD preview's cloth-cloth contact: the CCD filter applied at the end of each time
// step (pd-dd section 8, following C-IPC), as a rollback instead of a line search.
//   Every vertex moves linearly over the step from its start position (assumed free of intersections) to its end
//   position. Broad phase: two LBVHs (collision/bvh.h) over the triangles' and the edges' boxes swept from start
//   to end, grown by the CCD tolerance; each vertex's swept box is queried against the triangles, each edge's
//   against the edges. Narrow phase: vertex-triangle and edge-edge CCD (collision/ccd.h) on every pair whose
//   primitives share no vertex (stitched vertices count as one).
//   enforce(): every pair that touches during the step has its movable vertices put back at their start
//   positions (no motion this step); the pairs holding a moved vertex are tested again, until no pair touches.
//   A rollback only shrinks swept boxes, so the candidates stay valid; each vertex is rolled back at most once,
//   so the loop ends, at worst with every movable vertex at its start. All lists are sorted: the result does not
//   depend on the thread count or scheduling.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <utility>
#include <vector>

#include "drape/collision/bvh.h"

namespace drape::pd {

struct ClothGuardStats {
  int vertexTriangleCandidates = 0;  // pairs whose swept boxes overlap
  int edgeEdgeCandidates = 0;
  int hits = 0;        // pairs touching during the step before any rollback
  int rolledBack = 0;  // vertices put back at their start position
  int passes = 0;      // CCD passes (the first over every candidate, the others over the pairs of moved vertices)
  int remaining = 0;   // pairs still touching at the end: their vertices could not move back (pinned); 0 otherwise
};

// A pair found touching during the step. ids: (vertex, a, b, c) for a vertex-triangle pair (triangle = index),
// (p0, p1, q0, q1) for an edge-edge pair (first / second = edge indices).
struct ClothCcdHit {
  std::array<int, 4> ids{};
  int first = 0;   // vertex-triangle: the vertex; edge-edge: the first edge
  int second = 0;  // vertex-triangle: the triangle; edge-edge: the second edge
  double t = 1.0;  // time of impact in [0, 1]
};

class ClothCcdGuard {
 public:
  // triangles: |F| x 3; edges: the unique edges (vertex pairs); canonical: per vertex, the representative of its
  // stitched group (pairs sharing a representative are adjacent and never tested). tolerance: contact distance
  // of the CCD, metres.
  ClothCcdGuard(const Eigen::MatrixX3i& triangles, std::vector<std::pair<int, int>> edges,
                std::vector<int> canonical, double tolerance = 1e-6);

  // Pairs touching during start -> x (both |V| x 3), sorted (vertex-triangle by vertex then triangle, edge-edge by
  // edge ids). x is not changed.
  void findContacts(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& x, std::vector<ClothCcdHit>& vertexTriangle,
                    std::vector<ClothCcdHit>& edgeEdge);

  // Moves vertices of x back to start until no pair touches during start -> x (see above). movable(v): false for
  // vertices that must not move back (pinned: their motion is prescribed). exempt: sorted (vertex, triangle) pairs
  // that may touch (a vertex known to be on the wrong side of a triangle at the start, moving back through it).
  ClothGuardStats enforce(const Eigen::MatrixX3d& start, Eigen::MatrixX3d& x, const std::function<bool(int)>& movable,
                          const std::vector<std::pair<int, int>>& exempt = {});

 private:
  // Candidate pairs of the swept boxes start -> x, sorted; vertex ids per pair in m_candidates.
  void gatherCandidates(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& x);
  // CCD of candidate i over start -> x; time of impact in t.
  bool touches(int i, const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& x, double& t) const;

  Eigen::MatrixX3i m_triangles;
  std::vector<std::pair<int, int>> m_edges;
  std::vector<int> m_canonical;
  double m_tolerance;
  collision::Bvh m_triangleTree;
  collision::Bvh m_edgeTree;
  int m_refits = -1;  // refits since the last build; -1 = not built
  // Candidates: vertex-triangle first (m_vertexTriangleCount of them), then edge-edge. key = (first, second).
  std::vector<std::array<int, 4>> m_candidates;
  std::vector<std::pair<int, int>> m_keys;
  int m_vertexTriangleCount = 0;
  Eigen::MatrixX3d m_gathered, m_gatheredStart;  // positions of the last gathering (end, start)
  std::vector<char> m_lastHits;                   // CCD results of findContacts() on those candidates
};

}  // namespace drape::pd
