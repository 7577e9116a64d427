// The drape quality verdict (sim/drape_quality.h) against independent computations on hand-made configurations:
// crossing triangles counted once, seams and shared vertices not counted, a brute-force edge-through-triangle count
// on random triangles, a vertex at a known depth inside a box collider, a known stretch, and the rest requirement.
#include "drape/sim/drape_quality.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "drape/collision/avatar_collider.h"
#include "drape/collision/self_intersection.h"
#include "drape/geometry/primitives.h"
#include "drape/scene/settings.h"

namespace drape {
namespace {

using Eigen::Vector3d;

// A garment of the given triangles and positions, every rest triangle the unit right triangle (so a placed triangle
// congruent to it is unstretched), each triangle its own panel.
Garment looseTriangles(const Eigen::MatrixX3d& positions) {
  Garment g;
  const int nt = static_cast<int>(positions.rows() / 3);
  g.positions = positions;
  g.rest.resize(positions.rows(), 2);
  g.triangles.resize(nt, 3);
  g.trianglePanel.resize(nt);
  g.vertexPanel.resize(positions.rows());
  for (int t = 0; t < nt; ++t) {
    g.triangles.row(t) << 3 * t, 3 * t + 1, 3 * t + 2;
    g.rest.row(3 * t) << 0, 0;
    g.rest.row(3 * t + 1) << 1, 0;
    g.rest.row(3 * t + 2) << 0, 1;
    g.trianglePanel[t] = t;
    g.vertexPanel.segment<3>(3 * t).setConstant(t);
    g.panelNames.push_back("p" + std::to_string(t));
  }
  g.uvs = g.rest;
  return g;
}

const QualityCheck& check(const QualityReport& r, const std::string& name) {
  const QualityCheck* c = r.find(name);
  if (!c) throw std::runtime_error("no check " + name);
  return *c;
}

// Two unit right triangles: the first in the plane z = 0, the second in x = 0.25 crossing it.
Eigen::MatrixX3d crossingPair() {
  Eigen::MatrixX3d x(6, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
      0.25, 0.25, -0.5, 0.25, 0.25, 0.5, 0.25, -0.75, -0.5;
  return x;
}

TEST(SelfIntersections, TwoCrossingTrianglesCountOnce) {
  const Eigen::MatrixX3d x = crossingPair();
  EXPECT_TRUE(collision::trianglesIntersect(x.row(0), x.row(1), x.row(2), x.row(3), x.row(4), x.row(5)));
  const Garment g = looseTriangles(x);
  const collision::SelfIntersections found = collision::countSelfIntersections(x, g.triangles);
  EXPECT_EQ(found.count, 1);
  EXPECT_EQ(found.firstTriangle, 0);
  EXPECT_EQ(found.secondTriangle, 1);

  // Moved 1 m along z, the second triangle misses the first.
  Eigen::MatrixX3d apart = x;
  apart.bottomRows(3).col(2).array() += 1.0;
  EXPECT_EQ(collision::countSelfIntersections(apart, g.triangles).count, 0);

  QualitySettings strict;
  strict.maxSelfIntersections = 0;
  const QualityReport report = checkDrapeQuality(g, x, nullptr, 0.002, "AtRest", strict);
  EXPECT_FALSE(report.passed);
  const QualityCheck& c = check(report, "self_intersections");
  EXPECT_EQ(c.value, 1.0);
  EXPECT_FALSE(c.passed);
  EXPECT_EQ(c.triangle, 0);
  EXPECT_EQ(c.otherTriangle, 1);
  EXPECT_NE(c.message.find("triangle 0 of panel 'p0' and triangle 1 of panel 'p1'"), std::string::npos) << c.message;
  QualitySettings lenient;
  lenient.maxSelfIntersections = 1;
  EXPECT_TRUE(check(checkDrapeQuality(g, x, nullptr, 0.002, "AtRest", lenient), "self_intersections").passed);
}

TEST(SelfIntersections, SharedAndSewnVerticesAreNeighbours) {
  // Two triangles folded onto each other along a shared edge touch everywhere on it: neighbours, not a crossing.
  Eigen::MatrixX3d x(4, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.2, 0.2, 0.0;
  Eigen::MatrixX3i shared(2, 3);
  shared << 0, 1, 2, 1, 0, 3;
  EXPECT_EQ(collision::countSelfIntersections(x, shared).count, 0);

  // A sewn seam: two panels, each with its own copy of the seam's vertices at the same place. Unsewn they touch
  // (an intersection); with the stitch pairs they are neighbours.
  Eigen::MatrixX3d seam(6, 3);
  seam << 0, 0, 0, 1, 0, 0, 0, 1, 0,   // panel A
      1, 0, 0, 0, 0, 0, 0.5, -1, 0.3;  // panel B: its first two vertices are A's seam vertices 1 and 0
  Garment g = looseTriangles(seam);
  EXPECT_EQ(collision::countSelfIntersections(seam, g.triangles).count, 1);
  g.stitchPairs = {{1, 3}, {0, 4}};
  EXPECT_EQ(collision::countSelfIntersections(seam, g.triangles, g.stitchPairs).count, 0);
  EXPECT_EQ(check(checkDrapeQuality(g, seam, nullptr, 0.002, "AtRest", QualitySettings{}), "self_intersections").value,
            0.0);
  // One stitch pair is enough: the triangles then share a vertex.
  g.stitchPairs = {{0, 4}};
  EXPECT_EQ(collision::countSelfIntersections(seam, g.triangles, g.stitchPairs).count, 0);
}

// Whether segment pq passes through the interior of triangle abc (general position: no touching).
bool segmentCrossesTriangle(const Vector3d& p, const Vector3d& q, const Vector3d& a, const Vector3d& b,
                            const Vector3d& c) {
  const auto volume = [](const Vector3d& o, const Vector3d& u, const Vector3d& v, const Vector3d& w) {
    return (u - o).dot((v - o).cross(w - o));
  };
  const double sp = volume(a, b, c, p), sq = volume(a, b, c, q);
  if (sp * sq >= 0) return false;  // both ends on one side of the plane
  const double e0 = volume(p, q, a, b), e1 = volume(p, q, b, c), e2 = volume(p, q, c, a);
  return (e0 > 0 && e1 > 0 && e2 > 0) || (e0 < 0 && e1 < 0 && e2 < 0);
}

TEST(SelfIntersections, RandomTrianglesMatchABruteForceEdgeCount) {
  // Two triangles in general position intersect exactly when an edge of one passes through the other.
  std::mt19937 rng(46);
  std::uniform_real_distribution<double> centre(0.0, 1.0), corner(-0.12, 0.12);
  const int n = 300;
  Eigen::MatrixX3d x(3 * n, 3);
  for (int t = 0; t < n; ++t) {
    const Vector3d c(centre(rng), centre(rng), centre(rng));
    for (int k = 0; k < 3; ++k) x.row(3 * t + k) = (c + Vector3d(corner(rng), corner(rng), corner(rng))).transpose();
  }
  const Garment g = looseTriangles(x);
  int expected = 0;
  for (int t = 0; t < n; ++t)
    for (int u = t + 1; u < n; ++u) {
      bool crossing = false;
      for (int k = 0; k < 3 && !crossing; ++k) {
        crossing = segmentCrossesTriangle(x.row(3 * t + k), x.row(3 * t + (k + 1) % 3), x.row(3 * u), x.row(3 * u + 1),
                                          x.row(3 * u + 2)) ||
                   segmentCrossesTriangle(x.row(3 * u + k), x.row(3 * u + (k + 1) % 3), x.row(3 * t), x.row(3 * t + 1),
                                          x.row(3 * t + 2));
      }
      expected += crossing;
    }
  ASSERT_GT(expected, 10);  // the configuration does test something
  EXPECT_EQ(collision::countSelfIntersections(x, g.triangles).count, expected);
}

TEST(DrapeQuality, VertexInsideABoxColliderHasItsDepth) {
  // A box [-0.5, 0.5]^3; one vertex of three 5 mm below its top face, far from its other faces.
  const collision::AvatarCollider box(makeBox(Vector3d::Constant(-0.5), Vector3d::Constant(0.5)));
  Eigen::MatrixX3d x(3, 3);
  x << 0.0, 0.495, 0.0,  //
      0.3, 0.6, 0.0,     //
      0.0, 0.6, 0.3;
  const Garment g = looseTriangles(x);
  QualitySettings s;
  const QualityReport report = checkDrapeQuality(g, x, &box, 0.002, "AtRest", s);
  const QualityCheck& depth = check(report, "penetration_depth");
  EXPECT_NEAR(depth.value, 0.005, 1e-12);
  EXPECT_EQ(depth.vertex, 0);
  EXPECT_EQ(depth.threshold, 0.002);  // 0: the contact thickness
  EXPECT_FALSE(depth.passed);
  EXPECT_NE(depth.message.find("5.0 mm inside"), std::string::npos) << depth.message;
  const QualityCheck& inside = check(report, "inside_fraction");
  EXPECT_NEAR(inside.value, 1.0 / 3.0, 1e-15);
  EXPECT_FALSE(inside.passed);
  EXPECT_NEAR(check(report, "near_skin_fraction").value, 1.0 / 3.0, 1e-15);
  EXPECT_FALSE(report.passed);

  // An explicit depth threshold above 5 mm and fractions above a third pass.
  s.maxPenetrationDepth = 0.006;
  s.maxInsideFraction = 0.34;
  s.maxNearSkinFraction = 0.34;
  const QualityReport lenient = checkDrapeQuality(g, x, &box, 0.002, "AtRest", s);
  EXPECT_TRUE(check(lenient, "penetration_depth").passed);
  EXPECT_EQ(check(lenient, "penetration_depth").threshold, 0.006);
  EXPECT_TRUE(lenient.passed) << lenient.checks.front().message;

  // 0.5 mm above the top face: not inside, but near the skin (1 mm).
  x(0, 1) = 0.5005;
  const QualityReport near = checkDrapeQuality(g, x, &box, 0.002, "AtRest", QualitySettings{});
  EXPECT_EQ(check(near, "inside_fraction").value, 0.0);
  EXPECT_EQ(check(near, "penetration_depth").value, 0.0);
  EXPECT_TRUE(check(near, "penetration_depth").passed);
  EXPECT_NEAR(check(near, "near_skin_fraction").value, 1.0 / 3.0, 1e-15);
  EXPECT_FALSE(check(near, "near_skin_fraction").passed);

  // Without a collider there is nothing to be inside of: no such checks.
  const QualityReport none = checkDrapeQuality(g, x, nullptr, 0.002, "AtRest", QualitySettings{});
  EXPECT_EQ(none.find("inside_fraction"), nullptr);
  EXPECT_EQ(none.find("penetration_depth"), nullptr);
  EXPECT_EQ(none.find("near_skin_fraction"), nullptr);
  EXPECT_TRUE(none.passed);
}

TEST(DrapeQuality, FacesTurnedIntoTheColliderFailOutwardFaces) {
  // Four triangles lying 5 mm above the top face of a box [-0.5, 0.5]^3, wound counter-clockwise seen from above
  // (outward), and one 5 cm above (not on the collider: it does not count).
  const collision::AvatarCollider box(makeBox(Vector3d::Constant(-0.5), Vector3d::Constant(0.5)));
  Eigen::MatrixX3d x(15, 3);
  for (int t = 0; t < 5; ++t) {
    const double y = t < 4 ? 0.505 : 0.55, x0 = -0.4 + 0.15 * t;
    x.row(3 * t) << x0, y, 0.0;
    x.row(3 * t + 1) << x0 + 0.1, y, -0.1;
    x.row(3 * t + 2) << x0, y, -0.1;
  }
  Garment g = looseTriangles(x);
  for (int t = 0; t < 5; ++t) {
    const Vector3d a = x.row(3 * t), b = x.row(3 * t + 1), c = x.row(3 * t + 2);
    ASSERT_GT((b - a).cross(c - a).y(), 0.0);  // the premise: up, away from the box
  }
  const QualityReport right = checkDrapeQuality(g, x, &box, 0.002, "AtRest", QualitySettings{});
  EXPECT_EQ(check(right, "outward_faces").value, 1.0);
  EXPECT_TRUE(check(right, "outward_faces").passed);
  EXPECT_EQ(check(right, "outward_faces").triangle, -1);
  // Triangle 2 turned over: 3 of the 4 faces on the box face away from it; the one above still does not count.
  std::swap(g.triangles(2, 1), g.triangles(2, 2));
  std::swap(g.triangles(4, 1), g.triangles(4, 2));
  const QualityReport turned = checkDrapeQuality(g, x, &box, 0.002, "AtRest", QualitySettings{});
  EXPECT_DOUBLE_EQ(check(turned, "outward_faces").value, 0.75);
  EXPECT_FALSE(check(turned, "outward_faces").passed);
  EXPECT_EQ(check(turned, "outward_faces").triangle, 2);
  EXPECT_FALSE(turned.passed);
}

TEST(DrapeQuality, MaxStrainIsTheLargestPrincipalStretch) {
  // Triangle 0 congruent to its rest shape; triangle 1 stretched 1.3x along x and 1.1x along y.
  Eigen::MatrixX3d x(6, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
      2, 0, 0, 3.3, 0, 0, 2, 1.1, 0;
  const Garment g = looseTriangles(x);
  QualitySettings s;
  s.maxStrain = 0.25;
  const QualityReport report = checkDrapeQuality(g, x, nullptr, 0.002, "AtRest", s);
  const QualityCheck& strain = check(report, "max_strain");
  EXPECT_NEAR(strain.value, 0.3, 1e-12);
  EXPECT_EQ(strain.triangle, 1);
  EXPECT_FALSE(strain.passed);
  EXPECT_NE(strain.message.find("stretched 30.0 % (threshold 25.0 %), triangle 1 of panel 'p1'"), std::string::npos)
      << strain.message;
  s.maxStrain = 0.31;
  EXPECT_TRUE(checkDrapeQuality(g, x, nullptr, 0.002, "AtRest", s).passed);
}

TEST(DrapeQuality, RestIsRequiredUnlessSwitchedOff) {
  Eigen::MatrixX3d x(3, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  const Garment g = looseTriangles(x);
  QualitySettings s;
  EXPECT_TRUE(checkDrapeQuality(g, x, nullptr, 0.002, "AtRest", s).passed);
  const QualityReport timeUp = checkDrapeQuality(g, x, nullptr, 0.002, "MaxSimTime", s);
  EXPECT_FALSE(timeUp.passed);
  EXPECT_EQ(check(timeUp, "at_rest").value, 0.0);
  EXPECT_NE(check(timeUp, "at_rest").message.find("MaxSimTime"), std::string::npos);
  s.requireRest = false;
  EXPECT_TRUE(checkDrapeQuality(g, x, nullptr, 0.002, "MaxSimTime", s).passed);
  EXPECT_FALSE(checkDrapeQuality(g, x, nullptr, 0.002, "Diverged", QualitySettings{}).passed);
  // The balance of forces at the end, where it was measured, is in the check's line.
  const QualityCheck rest =
      check(checkDrapeQuality(g, x, nullptr, 0.002, "AtRest", s, RestMeasures{0.004, 0.062, 2.7e-5}), "at_rest");
  EXPECT_NE(rest.message.find("unbalanced force 0.4 % of the weight RMS, 6.2 % at most; the last step moved 0.027 mm"),
            std::string::npos)
      << rest.message;
  EXPECT_EQ(check(checkDrapeQuality(g, x, nullptr, 0.002, "AtRest", s), "at_rest").message.find("unbalanced"),
            std::string::npos);
}

TEST(DrapeQuality, SettingsAreRegisteredWithTheirDefaults) {
  Settings settings;
  const QualitySettings defaults;
  const QualitySettings s = qualitySettingsFrom(settings);
  EXPECT_EQ(s.maxStrain, defaults.maxStrain);
  EXPECT_EQ(s.maxInsideFraction, defaults.maxInsideFraction);
  EXPECT_EQ(s.maxPenetrationDepth, defaults.maxPenetrationDepth);
  EXPECT_EQ(s.nearSkinDistance, defaults.nearSkinDistance);
  EXPECT_EQ(s.maxNearSkinFraction, defaults.maxNearSkinFraction);
  EXPECT_EQ(s.maxSelfIntersections, defaults.maxSelfIntersections);
  EXPECT_EQ(s.requireRest, defaults.requireRest);
  settings.set("quality.require_rest", "false", "test");
  settings.set("quality.max_strain", "0.7", "test");
  EXPECT_FALSE(qualitySettingsFrom(settings).requireRest);
  EXPECT_EQ(qualitySettingsFrom(settings).maxStrain, 0.7);
}

}  // namespace
}  // namespace drape
