// The batched strain targets (strainTargets, the Jacobi local step's kernel) against strainTarget one triangle at a
// time, on random deformations from round to collapsed, with and without clamping and shear constraints.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <random>

#include "drape/pd/strain_projection.h"

using namespace drape::pd;

namespace {

using Target = Eigen::Matrix<double, 3, 2>;

// Triangles over random vertices: each a random rigid motion of a rest triangle, stretched by (1 + e, aspect), so
// that F covers the closed form and the near-collapse fallback. Every third triangle has a shear constraint.
struct RandomTriangles {
  Eigen::MatrixX3d x;
  std::vector<StrainConstraint> strains;
};

RandomTriangles randomTriangles(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double aspects[] = {1.0, 0.5, 1e-2, 1e-3, 5e-4, 1e-6, 0.0};
  RandomTriangles out;
  out.x.resize(3 * count, 3);
  for (int t = 0; t < count; ++t) {
    // Rest triangle (0,0), (L,0), (0,L) in the material frame: g is the gradient of the shape functions.
    const double rest = 0.01 + 0.02 * uniform(rng);
    StrainConstraint sc;
    sc.vertices = {3 * t, 3 * t + 1, 3 * t + 2};
    sc.g << -1.0 / rest, -1.0 / rest, 1.0 / rest, 0.0, 0.0, 1.0 / rest;
    sc.weightWarp = uniform(rng);
    sc.weightWeft = uniform(rng);
    sc.weightShear = t % 3 == 0 ? uniform(rng) : 0.0;
    out.strains.push_back(sc);
    const Eigen::Matrix3d q =
        Eigen::AngleAxisd(3.0 * normal(rng), Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized())
            .toRotationMatrix();
    const double aspect = aspects[t % 7];
    Eigen::Matrix2d stretch;
    stretch << 1.0 + 0.2 * normal(rng), 0.1 * normal(rng), 0.0, aspect * (1.0 + 0.2 * normal(rng));
    const Eigen::Matrix<double, 3, 2> f = q.leftCols<2>() * stretch;
    const Eigen::Vector3d origin(normal(rng), normal(rng), normal(rng));
    out.x.row(3 * t) = origin.transpose();
    out.x.row(3 * t + 1) = (origin + rest * f.col(0)).transpose();
    out.x.row(3 * t + 2) = (origin + rest * f.col(1)).transpose();
  }
  return out;
}

Target oneByOne(const StrainConstraint& sc, const Eigen::MatrixX3d& x, const StretchLimits& warp,
                const StretchLimits& weft, double shearLimit, bool holds) {
  Eigen::Matrix3d xs;
  for (int k = 0; k < 3; ++k) xs.row(k) = x.row(sc.vertices[k]);
  return strainTarget(sc, xs.transpose() * sc.g, warp, weft, shearLimit, holds);
}

}  // namespace

TEST(StrainTargets, BatchedEqualOneByOneOnRandomTriangles) {
  const RandomTriangles tri = randomTriangles(301, 5);
  const int n = static_cast<int>(tri.strains.size());
  const StretchLimits loose{0.0, 1e9}, tight{0.95, 1.05};
  int compared = 0, clamped = 0;
  for (bool holds : {false, true})
    for (const auto& limits : {loose, tight})
      // Ranges that start and end off the batch size, and one shorter than a batch.
      for (const auto& [begin, end] : {std::pair{0, n}, std::pair{3, n - 2}, std::pair{17, 22}}) {
        std::vector<Target> out(end - begin + 1, Target::Constant(7.0));
        strainTargets(tri.strains, tri.x, begin, end, limits, limits, 0.04, holds, out.data());
        EXPECT_EQ(out.back(), Target::Constant(7.0)) << "wrote past the range";
        for (int t = begin; t < end; ++t) {
          const Target& got = out[t - begin];
          const Target expected = oneByOne(tri.strains[t], tri.x, limits, limits, 0.04, holds);
          ASSERT_TRUE(got.allFinite()) << "triangle " << t;
          EXPECT_LE((got - expected).norm(), 1e-13 * (1.0 + expected.norm()))
              << "triangle " << t << " holds " << holds << " tight " << (limits.max < 2.0);
          ++compared;
          // Tight limits with the shear held by the stretch: P = R S' with S' symmetric, diagonal in [0.95, 1.05]
          // and off-diagonal within 0.04, so P's singular values lie in [0.91, 1.09].
          if (holds && limits.max < 2.0 && tri.strains[t].weightShear == 0.0) {
            const Eigen::Vector2d sv = Eigen::JacobiSVD<Target>(got).singularValues();
            EXPECT_GE(sv.minCoeff(), 0.91 - 1e-9) << "triangle " << t;
            EXPECT_LE(sv.maxCoeff(), 1.09 + 1e-9) << "triangle " << t;
            ++clamped;
          }
        }
      }
  EXPECT_EQ(compared, 4 * (n + (n - 5) + 5));
  EXPECT_GT(clamped, 200);
}
