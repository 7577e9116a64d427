#pragma once
// Domains of the decomposed solve (pd-dd sections 4.1, 4.3): METIS k-way partition of the triangle graph, and
// the split of the system matrix K of eq. 3 into per-domain matrices K^j with sum_j P_j^T K^j P_j = K.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include "drape/model/cloth_model.h"

namespace drape::pd {

class PdSystem;

// Per-triangle domain id in [0, domains) from METIS k-way on the graph whose nodes are triangles and whose
// edges join triangles sharing a mesh edge or linked by a stitch: a vertex stitch links a triangle of each end,
// an edge stitch a triangle of its vertex with the triangles of its edge (a, b) (or, when (a, b) is no mesh
// edge, with a triangle of a and one of b). domains is clamped to [1, |T|].
std::vector<int> partitionTriangles(const Eigen::MatrixX3i& triangles, int vertexCount,
                                    const std::vector<std::pair<int, int>>& stitches,
                                    const std::vector<model::EdgeStitch>& edgeStitches, int domains,
                                    unsigned seed = 1);
// The same without edge stitches.
std::vector<int> partitionTriangles(const Eigen::MatrixX3i& triangles, int vertexCount,
                                    const std::vector<std::pair<int, int>>& stitches, int domains,
                                    unsigned seed = 1);

// One domain's share of K: the stencils owned by its triangles plus M / h^2 split evenly among the domains that
// hold a vertex. An edge stitch's stencil is owned by a triangle of its edge (PdSystem), so its vertex v is held
// by that domain too: a non-conforming seam crossing domains makes v a duplicate (or corner) DOF, and the
// decomposed solve stays exact because sum_j P_j^T K^j P_j = K still holds.
// dofs: local -> global free DOF index (increasing); k: |dofs| x |dofs|.
struct DomainMatrix {
  std::vector<int> dofs;
  Eigen::SparseMatrix<double> k;
};

// Splits system.matrix() by triangle domains (|T| ids in [0, domains)). Free DOFs in no stencil go to domain 0.
std::vector<DomainMatrix> splitSystem(const PdSystem& system, const std::vector<int>& triangleDomain,
                                      int domains);

}  // namespace drape::pd
