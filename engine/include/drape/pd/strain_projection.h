#pragma once
// The strain constraints of the preview (pd-dd eq. 2) and their projections, the local step's arithmetic.
#include <Eigen/Core>
#include <array>
#include <vector>

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
// The target of one triangle at deformation gradient f: combinedTarget of both projections, or the stretch
// projection alone when the triangle has no shear constraint (weightShear 0).
Eigen::Matrix<double, 3, 2> strainTarget(const StrainConstraint& sc, const Eigen::Matrix<double, 3, 2>& f,
                                         const StretchLimits& warp, const StretchLimits& weft, double shearLimit,
                                         bool stretchHoldsShear = false);
// strainTarget of strains[t] for t in [begin, end) at positions x (|V| x 3) into out[t - begin]. The closed-form
// polar decompositions of stretch-only triangles run eight at a time over plain arrays, which the compiler
// vectorises (the one-by-one loop spends most of its time waiting on two dependent square roots per triangle);
// the others take strainTarget.
void strainTargets(const std::vector<StrainConstraint>& strains, const Eigen::MatrixX3d& x, int begin, int end,
                   const StretchLimits& warp, const StretchLimits& weft, double shearLimit, bool stretchHoldsShear,
                   Eigen::Matrix<double, 3, 2>* out);

}  // namespace drape::pd
