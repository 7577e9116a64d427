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
//   End of the step (resolve): the step's final positions are projected, Gauss-Seidel over the sided pairs, so
//   that every vertex in a triangle's prism is at least the thickness in front of it on its side; the correction
//   is shared between the vertex and the triangle's vertices by inverse mass (the C-IPC-style end-of-step filter
//   of pd-dd section 8, as a projection instead of a line search).
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "drape/collision/bvh.h"
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
  int remaining = 0;      // sided pairs still crossed after the last sweep
  int sweeps = 0;         // Gauss-Seidel sweeps made
  int ccdCrossings = 0;   // unsided pairs found crossed by CCD (then resolved as sided)
  int edgeCrossings = 0;  // edge-edge pairs found crossed by CCD during the step (then resolved)
};

class ClothContacts {
 public:
  // triangles: |F| x 3 over vertexCount vertices; stitches: vertex pairs counted as one vertex (a closed seam
  // must not repel itself); dofOfVertex: free DOF per vertex, -1 for pinned vertices (never constrained).
  ClothContacts(const Eigen::MatrixX3i& triangles, int vertexCount, const std::vector<std::pair<int, int>>& stitches,
                std::vector<int> dofOfVertex, const ClothContactOptions& options);

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
  // start: |V| x 3, the step's start (that beginStep saw). A pair whose vertex was outside the prism at the start
  // but ends inside on the other side is resolved too when CCD (collision/ccd.h, vertex against the moving
  // triangle, start -> x) confirms it went through the triangle; it is then remembered as sided.
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
  // Edge-edge pairs (edges incident to a pair's vertex against the pair triangle's edges) with the sign of
  // (q0 - p0) . ((p1 - p0) x (q1 - q0)) at the step start; a sign change plus a CCD hit is a crossing.
  struct EdgePair {
    int first = 0;  // edge ids (m_edges)
    int second = 0;
    double side = 1.0;
  };
  void gatherEdgePairs(const Eigen::MatrixX3d& start);
  // Projects the crossed edge pairs (edge-edge CCD over start -> x) back to goal on their start side; returns
  // the number of pairs moved.
  int resolveEdges(const Eigen::MatrixX3d& start, Eigen::MatrixX3d& x, const std::function<double(int)>& inverseMass,
                   double goal, bool firstSweep, std::vector<char>& crossed) const;

  Eigen::MatrixX3i m_triangles;
  std::vector<int> m_dofOfVertex;
  std::vector<int> m_canonical;  // merged-vertex representative
  ClothContactOptions m_options;
  collision::Bvh m_tree;
  int m_stepsSinceBuild = -1;
  std::vector<Pair> m_pairs;
  // Side of each sided pair, carried from step to step; key = vertex * |F| + triangle.
  std::unordered_map<std::uint64_t, double> m_sides;
  std::vector<std::pair<int, int>> m_edges;         // unique edges (vertex pairs, smaller first)
  std::vector<std::vector<int>> m_vertexEdges;      // per vertex: incident edge ids
  std::vector<std::array<int, 3>> m_triangleEdges;  // per triangle: its edge ids
  std::vector<EdgePair> m_edgePairs;
};

}  // namespace drape::pd
