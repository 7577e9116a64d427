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

// Triangle strain constraints: F = X^T g (X: 3 vertices x 3 coordinates, g: 3 x 2 shape-function gradients in
// the material frame), F = R S its polar decomposition. Two PD constraints per triangle, both of the form
// sum_c (w / 2) |F_c - P_c|^2 over the warp (c = 0) and weft (c = 1) columns:
//   stretch: weights weightWarp, weightWeft; P = R S with the diagonal of S clamped into the stretch limits
//            (resists only stretch beyond the limits);
//   shear:   weight weightShear on both columns; P = R S with the off-diagonal of S clamped into +-shearLimit
//            (resists only shear).
// For a small strain S = I + e the energy is A/2 (kWarp e00^2 + kWeft e11^2) + A kShear e01^2, the small-strain
// limit of the StVK membrane's A/2 (kWarp E00^2 + kWeft E11^2 + 2 kShear E01^2) (stvk_membrane.h): the shear
// weight is the fabric's shear stiffness times the area, factor 1. Summed, column c is one constraint of weight
// columnWeight(c) towards the weighted mean of the two projections (combinedTarget), so K, the right-hand side
// and the local steps see a single 3 x 2 target per triangle. With ShearModelKind::Stretch (pd-dd's constraint)
// weightShear is 0 and the stretch projection clamps the off-diagonal too: P = R clamp(S).
struct StrainConstraint {
  std::array<int, 3> vertices{};
  Eigen::Matrix<double, 3, 2> g = Eigen::Matrix<double, 3, 2>::Zero();  // 1/m
  double weightWarp = 0.0;   // stretchWarp * rest area, N m
  double weightWeft = 0.0;   // stretchWeft * rest area, N m
  double weightShear = 0.0;  // shear * rest area, N m (0 with ShearModelKind::Stretch)
  // Weight of column c (0 warp, 1 weft) in K and the right-hand side: stretch + shear, N m.
  double columnWeight(int c) const { return (c == 0 ? weightWarp : weightWeft) + weightShear; }
};

// The two projections of one triangle's F (3 x 2 each): see StrainConstraint.
struct StrainProjection {
  Eigen::Matrix<double, 3, 2> stretch;  // R [clamp(S00), S01; S10, clamp(S11)]
  Eigen::Matrix<double, 3, 2> shear;    // R [S00, clamp(s); clamp(s), S11], s = (S01 + S10) / 2
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

// Strain projections of pd-dd eq. 2 for one triangle: R (3 x 2, orthonormal columns) is the polar rotation of
// F (on a collapsed F an orthonormal frame from its longer column), S = R^T F. F: 3 x 2 deformation gradient.
// stretchHoldsShear (ShearModelKind::Stretch): the stretch projection clamps the off-diagonal as well.
StrainProjection projectStrain(const Eigen::Matrix<double, 3, 2>& f, const StretchLimits& warp,
                               const StretchLimits& weft, double shearLimit, bool stretchHoldsShear = false);
// The combined target of a triangle: column c is (w_c P_stretch,c + w_shear P_shear,c) / (w_c + w_shear), the
// stretch projection when both weights are 0 (degenerate rest triangle: the target is never used).
Eigen::Matrix<double, 3, 2> combinedTarget(const StrainConstraint& sc, const StrainProjection& p);
// Energy of the strain constraints of one triangle at deformation gradient f (3 x 2), J: the sum of both
// constraints' (w / 2) |F_c - P_c|^2, not the combined one's (which drops a constant of the local step).
double strainEnergy(const StrainConstraint& sc, const Eigen::Matrix<double, 3, 2>& f, const StretchLimits& warp,
                    const StretchLimits& weft, double shearLimit, bool stretchHoldsShear = false);

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
  // ShearModelKind::Stretch: pd-dd's strain constraint (see projectStrain).
  bool stretchHoldsShear() const { return m_stretchHoldsShear; }

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
  Eigen::SparseMatrix<double> m_k, m_kfp;
  std::vector<int> m_incOffsets, m_incTriangles;
  // Per incidence (vertex v, triangle t): w_c g(v, c) for both columns c of t's target, t's share of A^T B y at v.
  std::vector<Eigen::Vector2d> m_incWeights;
};

}  // namespace drape::pd
