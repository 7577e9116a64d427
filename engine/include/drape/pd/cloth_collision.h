#pragma once
// Cloth-cloth contact constraints of the PD preview (pd-dd section 7.3): vertex-triangle proximity between
// non-adjacent primitives of the garment (two layers, or one layer folding onto itself), as position constraints
// (A_k = I) on the vertex only. The partner triangles' vertices get their own constraints from the pairs where
// they are the vertex, so both layers are pushed apart.
//   Broad phase, once per step: an LBVH over the triangles' boxes swept from the start of the step to the
//   inertial prediction, inflated by thickness + margin, queried with each vertex's swept box.
//   Sides: a pair whose vertex lies, at the start of the step, inside the prism over the triangle (its projection
//   to the plane falls inside) and within thickness + margin of the plane is "sided": it keeps the side it had
//   when it was first seen so, over the following steps, as long as it stays in the prism (a vertex can only change
//   side there by crossing the triangle). A crossing left by one step is therefore undone by the next, never
//   locked in. Other pairs take their side from the start of the step.
//   Narrow phase, every L-G iteration: the vertex at its collision-free position against the triangle at the
//   current iterate (already corrected for contact). Face region: when the vertex is less than the thickness in
//   front of the plane on its side (or has crossed to the other side), the target is its projection to the plane
//   moved by the thickness to that side. Edge / vertex region on its side: pushed to the thickness away from the
//   closest point.
//   End of the step (resolve): the step's final positions are projected, Gauss-Seidel over the sided pairs and the
//   pairs found touching by CCD during the step, so that every vertex in a triangle's prism is at least the
//   thickness in front of it on its side; the correction is shared between the vertex and the triangle's vertices
//   by inverse mass. Then the CCD guard (cloth_ccd_guard.h, the end-of-step CCD filter of pd-dd section 8) puts
//   back at its start position every vertex whose motion over the step still touches another primitive, so a step
//   that starts free of intersections ends free of them. Pairs are visited in a sorted order: results do not
//   depend on thread scheduling.
//   When a step starts exactly where the last resolve() left the cloth (verified free of intersections), sides are
//   taken from the start positions; the remembered sides only serve a start that was not verified (the first step,
//   or a state left crossed).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "drape/collision/bvh.h"
#include "drape/model/cloth_model.h"
#include "drape/pd/cloth_ccd_guard.h"
#include "drape/pd/contact_solve.h"

namespace drape::pd {

struct ClothContactOptions {
  double thickness = 0.004;  // metres kept between two layers
  double margin = 0.02;      // metres added to the swept boxes of the broad phase
  double weight = 1e6;       // w_k, N/m
};

struct ClothContactStats {
  int contacts = 0;  // constraints added (before merging per vertex)
};

struct ClothResolveStats {
  int violations = 0;     // sided pairs closer than the thickness (or crossed) before the first sweep
  int crossed = 0;        // of which on the wrong side of their triangle
  int remaining = 0;      // pairs still touching during the step after the guard (0 unless pinned vertices cross)
  int sweeps = 0;         // Gauss-Seidel sweeps made
  int ccdCrossings = 0;   // vertex-triangle pairs touching during the step (CCD; then resolved as sided)
  int edgeCrossings = 0;  // edge-edge pairs touching during the step (CCD; then projected)
  int rolledBack = 0;     // vertices the guard put back at their start position
  int guardHits = 0;      // pairs the guard found touching after the projection, before rolling back
};

class ClothContacts {
 public:
  // triangles: |F| x 3 over vertexCount vertices; stitches: vertex pairs counted as one vertex (a closed seam
  // must not repel itself); dofOfVertex: free DOF per vertex, -1 for pinned vertices (never constrained);
  // edgeStitches (non-conforming seams): each vertex counts as one with the nearer end of its edge
  // (collision::contactMergedVertices).
  ClothContacts(const Eigen::MatrixX3i& triangles, int vertexCount, const std::vector<std::pair<int, int>>& stitches,
                std::vector<int> dofOfVertex, const ClothContactOptions& options,
                const std::vector<model::EdgeStitch>& edgeStitches = {});
  // Representative of v's merged group (stitched vertices share one; v itself when not stitched).
  int canonical(int v) const { return m_canonical[v]; }
  ~ClothContacts();

  // Start of a step: start and predicted are |V| x 3. Gathers the candidate pairs (parallel).
  void beginStep(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& predicted);
  int candidateCount() const { return static_cast<int>(m_pairs.size()); }

  // Adds constraints for the candidates: vertices at xFree (|free| x 3, collision-free solve), triangles at
  // current (|V| x 3, the last iterate).
  ClothContactStats addConstraints(const Eigen::MatrixX3d& xFree, const Eigen::MatrixX3d& current,
                                   ContactAccumulator& acc) const;

  // End of a step: moves x (|V| x 3, the step's result) so that each sided pair is at least the thickness apart
  // on its side (a pair closer than 3/4 of the thickness is pushed to 3/4 of it). inverseMass(v): weight of
  // vertex v in sharing a correction, 1/kg (0 = does not move, e.g. pinned). At most maxSweeps Gauss-Seidel sweeps
  // (serial); stops after the first sweep without a violation.
  // start: |V| x 3, the step's start (that beginStep saw). Vertex-triangle pairs that CCD (start -> x) finds
  // touching during the step are resolved as sided pairs with their start side (and remembered), edge-edge pairs
  // touching during the step are pushed back to their start side. Finally the CCD guard rolls back to start every
  // movable (inverseMass > 0) vertex whose motion still touches a primitive.
  ClothResolveStats resolve(const Eigen::MatrixX3d& start, Eigen::MatrixX3d& x,
                            const std::function<double(int)>& inverseMass, int maxSweeps = 8);

  // Number of vertex-triangle pairs whose vertex is on the wrong side of its triangle (in the prism), at x.
  int crossedPairs(const Eigen::MatrixX3d& x) const;

  const ClothContactOptions& options() const { return m_options; }

 private:
  struct Pair {
    int vertex = 0;
    int triangle = 0;
    double side = 1.0;   // +1 / -1: side of the triangle's plane (normal (b - a) x (c - a)) to keep
    bool sided = false;  // the vertex was in the triangle's prism at the step start (side is trusted)
  };
  bool adjacent(int vertex, int triangle) const;
  // The pair's vertex is on the wrong side of its triangle, in its prism (within the reach), at x.
  bool crossed(const Pair& pr, const Eigen::MatrixX3d& x) const;
  // Sided pair for a vertex-triangle pair CCD found touching; side from the start (or the remembered side).
  void addTouchingPair(const ClothCcdHit& hit, const Eigen::MatrixX3d& start, ClothResolveStats& stats);
  // Pushes the touching edge-edge pairs back to goal on their start side; returns the number of pairs moved.
  int resolveEdges(Eigen::MatrixX3d& x, const std::function<double(int)>& inverseMass, double goal) const;
  struct EdgePair {
    std::array<int, 4> ids{};  // p0, p1, q0, q1
    double side = 1.0;         // sign of (q0 - p0) . ((p1 - p0) x (q1 - q0)) at the step start
  };

  Eigen::MatrixX3i m_triangles;
  std::vector<int> m_dofOfVertex;
  std::vector<int> m_canonical;  // merged-vertex representative
  ClothContactOptions m_options;
  collision::Bvh m_tree;
  int m_stepsSinceBuild = -1;
  std::vector<Pair> m_pairs;
  // Side of each sided pair, carried from step to step; key = vertex * |F| + triangle.
  std::unordered_map<std::uint64_t, double> m_sides;
  std::vector<std::pair<int, int>> m_edges;  // unique edges (vertex pairs, smaller first)
  std::vector<EdgePair> m_edgePairs;         // edge-edge pairs touching during the step (resolve)
  std::unique_ptr<ClothCcdGuard> m_guard;
  Eigen::MatrixX3d m_lastResolved;  // x at the end of the last resolve() (free of intersections when verified)
  bool m_lastVerified = false;      // the guard left no touching pair in the last resolve()
  bool m_startVerified = false;     // beginStep's start is m_lastResolved, verified
};

}  // namespace drape::pd
