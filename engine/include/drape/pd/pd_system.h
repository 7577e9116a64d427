#pragma once
// The Projective Dynamics model of a cloth (pd-dd section 3): lumped masses, strain constraints per triangle,
// quadratic bending and zero-length stitches, pinned vertices eliminated from the unknowns. Every term acts on
// the three coordinates alike, so the system matrix K of eq. 3 is one scalar |free| x |free| matrix solved for
// three right-hand sides.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "drape/model/cloth_model.h"
#include "drape/pd/preview_settings.h"
#include "drape/pd/strain_projection.h"

namespace drape::pd {

// A constant quadratic term (1/2) x_s^T q x_s on up to 4 vertices (per coordinate): the strain constraint's
// A^T A part, a bending hinge (Bergou et al. 2006), a vertex stitch (2 vertices) or an edge stitch (3 vertices
// v, a, b with q = w A^T A, A = [1, -(1 - t), -t]; pd-dd section 4.4). ownerTriangle decides its domain: for an
// edge stitch a triangle of the edge (a, b) when there is one.
struct Stencil {
  std::array<int, 4> vertices{};
  int size = 0;
  Eigen::Matrix4d q = Eigen::Matrix4d::Zero();  // N/m
  int ownerTriangle = 0;
};

// Bergou et al. 2006 hinge vector k (4 entries) on rest coordinates: edge (r0, r1), opposite vertices r2 and
// r3 on either side; the hinge energy is (3 / (A0 + A1)) (k . x)^2 / 2 per coordinate, zero on flat shapes.
Eigen::Vector4d hingeVector(const Eigen::Vector2d& r0, const Eigen::Vector2d& r1, const Eigen::Vector2d& r2,
                            const Eigen::Vector2d& r3);

class PdSystem {
 public:
  // Validates sizes (throws InputError naming the element) and builds all constraints. h: time step, s.
  PdSystem(const model::ClothModel& model, const PreviewSettings& settings);

  int vertexCount() const { return m_vertexCount; }
  int freeCount() const { return static_cast<int>(m_freeVertices.size()); }
  int triangleCount() const { return static_cast<int>(m_triangles.rows()); }
  const Eigen::MatrixX3i& triangles() const { return m_triangles; }
  // vertex -> free DOF index, -1 for pinned vertices.
  const std::vector<int>& dofOfVertex() const { return m_dofOfVertex; }
  const std::vector<int>& freeVertices() const { return m_freeVertices; }
  const std::vector<int>& pinnedVertices() const { return m_pinned; }
  const Eigen::MatrixX3d& pinTargets() const { return m_pinTargets; }  // |pinned| x 3, metres
  // Moves the pins (the matrix does not depend on where they are). targets: |pinned| x 3, metres.
  void setPinTargets(const Eigen::MatrixX3d& targets);
  const Eigen::VectorXd& masses() const { return m_mass; }             // |V|, kg
  double timeStep() const { return m_h; }
  const std::vector<StrainConstraint>& strains() const { return m_strains; }
  const std::vector<Stencil>& stencils() const { return m_stencils; }
  const Eigen::Vector3d& gravity() const { return m_gravity; }
  const StretchLimits& warpLimits() const { return m_warp; }
  const StretchLimits& weftLimits() const { return m_weft; }
  double shearLimit() const { return m_shearLimit; }
  // ShearModelKind::Stretch: pd-dd's strain constraint (see projectStrain).
  bool stretchHoldsShear() const { return m_stretchHoldsShear; }
  // Largest warp or weft stretch stiffness of the model's fabrics, N/m (sets the default stitch weight).
  double largestStretch() const { return m_largestStretch; }

  // K of eq. 3 over the free DOFs, |free| x |free|: M / h^2 plus every stencil.
  const Eigen::SparseMatrix<double>& matrix() const { return m_k; }
  // Coupling of free to pinned DOFs, |free| x |pinned|: b gets -K_fp x_p.
  const Eigen::SparseMatrix<double>& pinCoupling() const { return m_kfp; }

  // Deformation gradient of triangle i at positions x (|V| x 3): 3 x 2.
  Eigen::Matrix<double, 3, 2> deformationGradient(int i, const Eigen::MatrixX3d& x) const;
  // Combined strain target of triangle i at positions x (|V| x 3).
  Eigen::Matrix<double, 3, 2> project(int i, const Eigen::MatrixX3d& x) const;
  // The same from triangle i's deformation gradient f (3 x 2).
  Eigen::Matrix<double, 3, 2> target(int i, const Eigen::Matrix<double, 3, 2>& f) const;
  // project(t, x) of triangles t in [begin, end) into out[t - begin] (strainTargets: batched).
  void projectRange(const Eigen::MatrixX3d& x, int begin, int end, Eigen::Matrix<double, 3, 2>* out) const;
  // Strain energy (stretch + shear constraints) of all triangles at positions x (|V| x 3), J.
  double strainEnergy(const Eigen::MatrixX3d& x) const;
  // Right-hand side of eq. 3 over the free DOFs (|free| x 3): M z / h^2 + sum_i w_i A_i^T B_i y_i - K_fp x_p.
  // z: |V| x 3 inertial prediction; targets: one 3 x 2 target per strain constraint.
  Eigen::MatrixX3d rhs(const Eigen::MatrixX3d& z, const std::vector<Eigen::Matrix<double, 3, 2>>& targets) const;
  // Triangles incident to each vertex (CSR: offsets |V|+1, indices).
  const std::vector<int>& incidentOffsets() const { return m_incOffsets; }
  const std::vector<int>& incidentTriangles() const { return m_incTriangles; }

 private:
  int m_vertexCount = 0;
  double m_h = 0.0;
  Eigen::MatrixX3i m_triangles;
  Eigen::VectorXd m_mass;
  Eigen::Vector3d m_gravity;
  std::vector<int> m_dofOfVertex, m_freeVertices, m_pinned;
  Eigen::MatrixX3d m_pinTargets;
  std::vector<StrainConstraint> m_strains;
  std::vector<Stencil> m_stencils;
  StretchLimits m_warp, m_weft;
  double m_shearLimit = 0.0;
  bool m_stretchHoldsShear = false;
  double m_largestStretch = 0.0;
  Eigen::SparseMatrix<double> m_k, m_kfp;
  std::vector<int> m_incOffsets, m_incTriangles;
  // Per incidence (vertex v, triangle t): w_c g(v, c) for both columns c of t's target, t's share of A^T B y at v.
  std::vector<Eigen::Vector2d> m_incWeights;
};

}  // namespace drape::pd
