// Friction of the PD preview's avatar contact (avatar_collision.h, issue 6) bounded by the inertial load does not hold
// a landing's stretch in place: the bench's tablecloth dropped onto a sphere, run with the current default and with
// the first version (ContactTargetKind::Reproject with FrictionLoadKind::CollisionFree), so the bounds below are shown
// to separate the two. The contact targets' other tests are in tests/unit/pd/pd_contact_target_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "drape/collision/avatar_collider.h"
#include "drape/geometry/primitives.h"
#include "drape/pd/grid_cloth.h"
#include "drape/pd/preview_solver.h"
#include "pd_contact_target_support.h"

namespace drape::pd {
namespace {

// Edge strains |x_i - x_j| / |r_i - r_j| - 1 of every triangle edge (rest lengths from the material coords).
std::vector<double> edgeStrains(const drape::model::ClothModel& model, const Eigen::MatrixX3d& x) {
  std::vector<double> s;
  for (int t = 0; t < model.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = model.triangles(t, k), b = model.triangles(t, (k + 1) % 3);
      s.push_back((x.row(a) - x.row(b)).norm() / (model.restCoords.row(a) - model.restCoords.row(b)).norm() - 1.0);
    }
  return s;
}

double quantile(std::vector<double> v, double q) {
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

// Friction: the bench's tablecloth (cotton shirting, 6000 / 4000 N/m) at its 1.5 cm spacing, dropped 0.2 m onto a
// sphere of radius 0.3 m, mu = 0.4.

TEST(PdContactTarget, FrictionDoesNotLockTheLandingStretch) {
  GridClothOptions o;
  o.nx = o.ny = 67;
  o.width = o.height = 1.0;
  o.horizontal = true;
  const double radius = 0.3;
  o.elevation = radius + 0.2;
  o.pinTopCorners = false;
  drape::model::ClothModel model = makeGridCloth(o);
  model.fabrics[0].stretchWarp = 6000.0;
  model.fabrics[0].stretchWeft = 4000.0;
  model.fabrics[0].shear = 40.0;
  auto collider = std::make_shared<const collision::AvatarCollider>(makeIcosphere(Eigen::Vector3d::Zero(), radius, 5));
  PreviewSettings s;
  s.domains = 2;
  s.threads = 2;
  s.friction = 0.4;
  s.maxHalvings = 0;  // both friction loads at the same step: a halved landing step stretches less either way
  // pd-dd's strain constraint, shear held by the stretch weights: the lock this test guards against shows in a
  // fabric stiff in shear. With the fabric's own shear (40 N/m) the cloth relaxes the landing by shearing and
  // neither friction load locks a stretch (measured: warp/weft edges p95 2.9 % vs 3.0 %; all edges 10 %, the
  // diagonals measuring the shear).
  s.shearModel = ShearModelKind::Stretch;
  // The sewn switch (a garment without stitches counts as sewn after 0.1 s) would set both to the collision-free load.
  s.sewnGap = 0.0;
  const int steps = 100;
  const SettleResult now = settle(model, s, collider, steps);
  const SettleResult before = settle(model, firstVersion(s), collider, steps);
  const auto report = [&](const char* name, const SettleResult& r) {
    const std::vector<double> e = edgeStrains(model, r.x);
    const int centre = 33 * 67 + 33;
    std::printf("[ PdContactTarget ] %-22s edge strain p50 %.4f p95 %.4f p99 %.4f max %.4f; centre vertex at "
                "(%.4f, %.4f, %.4f); lowest y %.4f\n", name, quantile(e, 0.5), quantile(e, 0.95), quantile(e, 0.99),
                quantile(e, 1.0), r.x(centre, 0), r.x(centre, 1), r.x(centre, 2), r.x.col(1).minCoeff());
    return quantile(e, 0.95);
  };
  const double p95 = report("friction (inertial)", now);
  const double p95Before = report("friction (first)", before);
  // Measured (2 threads): p95 3.1 % vs 5.8 %, p99 5.2 % vs 10.8 %, max 7.0 % vs 16.6 %. The rest of the stretch
  // is the landing's, which the preview's capped L-G iterations leave in a stiff fabric (frictionless, the
  // cloth slides off the sphere instead).
  EXPECT_LT(p95, 0.04);
  EXPECT_GT(p95Before, 0.04);  // the bound separates the two
  EXPECT_LT(p95, 0.7 * p95Before);
  // Still on the sphere: the centre vertex on its top (at the thickness), not slid sideways.
  const int centre = 33 * 67 + 33;
  EXPECT_NEAR(now.x.row(centre).norm(), radius + s.contactThickness, 0.003);
  EXPECT_LT(std::hypot(now.x(centre, 0), now.x(centre, 2)), 0.02);
  EXPECT_GT(now.deepest, -s.contactThickness);
}

}  // namespace
}  // namespace drape::pd
