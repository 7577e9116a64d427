#pragma once
// Local step of Projective Dynamics: the strain targets y_i of pd-dd eq. 2 for every triangle.
// Jacobi (vanilla PD baseline): every target from the same positions, in parallel.
// Gauss-Seidel (pd-dd section 5): domains in parallel; inside a domain the triangles are visited along the DFS
// order of one of several random spanning trees of the domain's constraint graph (triangles joined when they
// share a vertex), starting from triangles with pinned vertices, the order alternating between iterations.
// After each projection the triangle's free vertices are relaxed by a Gauss-Seidel update of K x = b with the
// newest targets (the small constraint-level system of eq. 12), and the next triangles project from them. One
// local step is a symmetric sweep: forward along the order, then back along it. A single forward sweep needs
// about as many L-G iterations as Jacobi (0-15% more on the hanging cloth): the point relaxation only reaches
// the high-frequency part of the error, and the one-sided order leaves a directional bias in the targets; the
// backward pass removes the bias and makes GS need fewer iterations than Jacobi (docs/BENCHMARKS.md).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "drape/pd/pd_system.h"

namespace drape::pd {

using StrainTarget = Eigen::Matrix<double, 3, 2>;

class LocalStep {
 public:
  // triangleDomain: |T| ids in [0, domains). orders: number of traversal orders per domain (>= 1).
  LocalStep(const PdSystem& system, const std::vector<int>& triangleDomain, int domains, int orders,
            unsigned seed);

  // targets[i] = projection of triangle i at x (|V| x 3). Parallel over triangles.
  void jacobi(const Eigen::MatrixX3d& x, std::vector<StrainTarget>& targets) const;
  // x: |V| x 3 positions after the last global step (pins at their targets); b: |free| x 3 right-hand side
  // assembled from `targets` (PdSystem::rhs). Updates targets in place. iteration selects the order.
  void gaussSeidel(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& b, int iteration,
                   std::vector<StrainTarget>& targets) const;

  int orderCount() const { return m_orders; }
  // Traversal order `o` of domain j as global triangle ids, for tests.
  std::vector<int> order(int j, int o) const;
  int domainCount() const { return static_cast<int>(m_domains.size()); }

 private:
  struct Domain {
    std::vector<int> vertices;                 // local -> global vertex
    std::vector<int> triangles;                // global triangle ids
    std::vector<std::array<int, 3>> local;     // per triangle: local vertex indices
    std::vector<std::vector<int>> orders;      // permutations of local triangle indices
    // K row of each local vertex (free ones): CSR over (neighbour, value). A neighbour outside the domain's
    // triangles is a ghost: local index vertices.size() + g for ghosts[g], read from the shared positions.
    std::vector<int> rowOffsets, rowNeighbour, ghosts;
    std::vector<double> rowValue, diagonal;
    std::vector<int> freeDof;                  // local -> free DOF or -1 (pinned)
  };
  const PdSystem& m_system;
  int m_orders = 1;
  std::vector<Domain> m_domains;
};

}  // namespace drape::pd
