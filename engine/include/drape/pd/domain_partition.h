#pragma once
// Domains of the decomposed solve (pd-dd sections 4.1, 4.3): METIS k-way partition of the triangle graph, and
// the split of the system matrix K of eq. 3 into per-domain matrices K^j with sum_j P_j^T K^j P_j = K.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

namespace drape::pd {

class PdSystem;

// Per-triangle domain id in [0, domains) from METIS k-way on the graph whose nodes are triangles and whose
// edges join triangles sharing a mesh edge or linked by a stitch. domains is clamped to [1, |T|].
std::vector<int> partitionTriangles(const Eigen::MatrixX3i& triangles, int vertexCount,
                                    const std::vector<std::pair<int, int>>& stitches, int domains,
                                    unsigned seed = 1);

// One domain's share of K: the stencils owned by its triangles plus M / h^2 split evenly among the domains that
// hold a vertex. dofs: local -> global free DOF index (increasing); k: |dofs| x |dofs|.
struct DomainMatrix {
  std::vector<int> dofs;
  Eigen::SparseMatrix<double> k;
};

// Splits system.matrix() by triangle domains (|T| ids in [0, domains)). Free DOFs in no stencil go to domain 0.
std::vector<DomainMatrix> splitSystem(const PdSystem& system, const std::vector<int>& triangleDomain,
                                      int domains);

}  // namespace drape::pd
