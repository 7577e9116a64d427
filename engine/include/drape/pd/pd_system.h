#pragma once
// The Projective Dynamics model of a cloth (pd-dd section 3): lumped masses, strain constraints per triangle,
// quadratic bending and zero-length stitches, pinned vertices eliminated from the unknowns. Every term acts on
// the three coordinates alike, so the system matrix K of eq. 3 is one scalar |free| x |free| matrix solved for
// three right-hand sides.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "drape/newton/cloth_model.h"
#include "drape/pd/preview_settings.h"

namespace drape::pd {

// Triangle strain constraint: F = X^T g (X: 3 vertices x 3 coordinates, g: 3 x 2 shape-function gradients in
// the material frame), energy sum_c (w_c / 2) |F_c - T_c|^2 over the warp (c = 0) and weft (c = 1) columns.
struct StrainConstraint {
  std::array<int, 3> vertices{};
  Eigen::Matrix<double, 3, 2> g = Eigen::Matrix<double, 3, 2>::Zero();  // 1/m
  double weightWarp = 0.0;  // stretchWarp * rest area, N m
  double weightWeft = 0.0;  // stretchWeft * rest area, N m
};

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

// Strain target of pd-dd eq. 2 for one triangle: the polar rotation R of F (3 x 2, orthonormal columns) times
// the stretch R^T F clamped into the limits per direction. F: 3 x 2 deformation gradient.
Eigen::Matrix<double, 3, 2> projectStrain(const Eigen::Matrix<double, 3, 2>& f, const StretchLimits& warp,
                                          const StretchLimits& weft, double shearLimit);

// Bergou et al. 2006 hinge vector k (4 entries) on rest coordinates: edge (r0, r1), opposite vertices r2 and
// r3 on either side; the hinge energy is (3 / (A0 + A1)) (k . x)^2 / 2 per coordinate, zero on flat shapes.
Eigen::Vector4d hingeVector(const Eigen::Vector2d& r0, const Eigen::Vector2d& r1, const Eigen::Vector2d& r2,
                            const Eigen::Vector2d& r3);

class PdSystem {
 public:
  // Validates sizes (throws InputError naming the element) and builds all constraints. h: time step, s.
  PdSystem(const newton::ClothModel& model, const PreviewSettings& settings);

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

  // K of eq. 3 over the free DOFs, |free| x |free|: M / h^2 plus every stencil.
  const Eigen::SparseMatrix<double>& matrix() const { return m_k; }
  // Coupling of free to pinned DOFs, |free| x |pinned|: b gets -K_fp x_p.
  const Eigen::SparseMatrix<double>& pinCoupling() const { return m_kfp; }

  // Strain target of constraint i at positions x (|V| x 3).
  Eigen::Matrix<double, 3, 2> project(int i, const Eigen::MatrixX3d& x) const;
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
  Eigen::SparseMatrix<double> m_k, m_kfp;
  std::vector<int> m_incOffsets, m_incTriangles;
};

}  // namespace drape::pd
