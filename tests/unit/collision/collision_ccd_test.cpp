// CCD: cubic roots by Halley and Newton against known roots (simple, double, triple, near-tangent), both methods
// against each other and against a dense sampling of the coplanarity cubic on random vertex-triangle and
// edge-edge motions, and hand-made impacts with known times.
#include <gtest/gtest.h>

#include <random>

#include "drape/collision/ccd.h"
#include "drape/collision/distance.h"

namespace drape::collision {
namespace {

using Eigen::Vector3d;

Cubic fromRoots(double a, double b, double c, double lead = 1.0) {
  // lead (t - a)(t - b)(t - c)
  Cubic f;
  f.c[3] = lead;
  f.c[2] = -lead * (a + b + c);
  f.c[1] = lead * (a * b + b * c + a * c);
  f.c[0] = -lead * a * b * c;
  return f;
}

TEST(CollisionCcdTest, CubicRootsKnownCases) {
  struct Case {
    Cubic f;
    std::vector<double> roots;
  };
  Cubic tangentMiss = fromRoots(0.4, 0.4, 5.0);
  tangentMiss.c[0] -= 1e-9;  // lifts the double root off the axis: no root in [0, 1]
  const Case cases[] = {
      {fromRoots(0.2, 0.5, 0.9), {0.2, 0.5, 0.9}},
      {fromRoots(0.3, 0.3, 0.8), {0.3, 0.8}},      // double root (touching)
      {fromRoots(0.5, 0.5, 0.5, -2.0), {0.5}},     // triple root
      {fromRoots(-1.0, 1.5, 2.0), {}},             // no root in [0, 1]
      {fromRoots(0.0, 0.6, 3.0), {0.0, 0.6}},      // root at the start
      {tangentMiss, {}},
      {fromRoots(0.25, 1e6, -1e6, 1e-12), {0.25}},  // badly scaled
  };
  for (const Case& k : cases) {
    for (RootMethod m : {RootMethod::Halley, RootMethod::Newton}) {
      std::array<double, 3> roots{};
      const int n = cubicRoots(k.f, 0.0, 1.0, m, roots);
      ASSERT_EQ(n, static_cast<int>(k.roots.size())) << k.f.c[0] << " " << k.f.c[1] << " " << k.f.c[2];
      for (int i = 0; i < n; ++i) EXPECT_NEAR(roots[i], k.roots[i], 1e-6) << "root " << i;
    }
  }
}

TEST(CollisionCcdTest, HalleyAndNewtonAgreeAndHalleyNeedsFewerIterations) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RootStats halley, newton;
  int rootsFound = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Cubic f;
    for (double& c : f.c) c = u(rng);
    std::array<double, 3> rh{}, rn{};
    const int nh = cubicRoots(f, 0.0, 1.0, RootMethod::Halley, rh, &halley);
    const int nn = cubicRoots(f, 0.0, 1.0, RootMethod::Newton, rn, &newton);
    ASSERT_EQ(nh, nn);
    for (int i = 0; i < nh; ++i) {
      EXPECT_NEAR(rh[i], rn[i], 1e-12);
      EXPECT_LE(std::abs(f(rh[i])), 1e-13);
    }
    rootsFound += nh;
    // Dense sampling: every sign change between samples lies within a sample spacing of a found root.
    constexpr int samples = 2000;
    for (int s = 0; s < samples; ++s) {
      const double a = double(s) / samples;
      const double b = double(s + 1) / samples;
      if ((f(a) < 0) != (f(b) < 0)) {
        bool near = false;
        for (int i = 0; i < nh; ++i) near |= rh[i] >= a - 1e-12 && rh[i] <= b + 1e-12;
        EXPECT_TRUE(near) << "missed a sign change in [" << a << ", " << b << "]";
      }
    }
  }
  EXPECT_GT(rootsFound, 500);
  EXPECT_LT(halley.iterations, newton.iterations);
  std::printf("[ stats    ] Halley %d vs Newton %d iterations over %d roots\n", halley.iterations, newton.iterations,
              rootsFound);
}

TEST(CollisionCcdTest, VertexTriangleHandMade) {
  const Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), zero = Vector3d::Zero();
  // Straight through the triangle: impact at t = 0.25.
  CcdResult r = vertexTriangleCcd(Vector3d(0.2, 0.2, 1), a, b, c, Vector3d(0, 0, -4), zero, zero, zero);
  EXPECT_TRUE(r.hit);
  EXPECT_NEAR(r.t, 0.25, 1e-12);
  // Crosses the plane outside the triangle: no impact.
  r = vertexTriangleCcd(Vector3d(2, 2, 1), a, b, c, Vector3d(0, 0, -4), zero, zero, zero);
  EXPECT_FALSE(r.hit);
  // The triangle moves onto a resting vertex.
  r = vertexTriangleCcd(Vector3d(0.3, 0.3, 0.5), a, b, c, zero, Vector3d(0, 0, 1), Vector3d(0, 0, 1), Vector3d(0, 0, 1));
  EXPECT_TRUE(r.hit);
  EXPECT_NEAR(r.t, 0.5, 1e-12);
  // Tangent: c rises (the plane tilts) while the vertex moves so that f(t) = (t - 0.5)^2, a double root; the
  // vertex touches the plane only at t = 0.5, inside the triangle (barycentric 0.6, 0.2, 0.2).
  r = vertexTriangleCcd(Vector3d(0.2, 0.7, 0.25), a, b, c, Vector3d(0, -1, -0.3), zero, zero, Vector3d(0, 0, 1));
  EXPECT_TRUE(r.hit);
  EXPECT_NEAR(r.t, 0.5, 1e-6);
  // The same with the vertex lifted by 1e-6 m: a near-tangent miss (f stays above zero).
  CcdOptions tight;
  tight.tolerance = 1e-12;
  r = vertexTriangleCcd(Vector3d(0.2, 0.7, 0.25 + 1e-6), a, b, c, Vector3d(0, -1, -0.3), zero, zero,
                        Vector3d(0, 0, 1), tight);
  EXPECT_FALSE(r.hit);
}

TEST(CollisionCcdTest, NearTangentEdgeEdge) {
  // Edge b slides over edge a and touches it exactly at t = 0.5 while staying parallel to a's plane.
  const Vector3d p0(-1, 0, 0), p1(1, 0, 0);
  const Vector3d q0(0, -1, 0.5), q1(0, 1, 0.5);
  const Vector3d zero = Vector3d::Zero();
  CcdResult r = edgeEdgeCcd(p0, p1, q0, q1, zero, zero, Vector3d(0, 0, -1), Vector3d(0, 0, -1));
  EXPECT_TRUE(r.hit);
  EXPECT_NEAR(r.t, 0.5, 1e-12);
  // The same motion stopping 1 micrometre short: no impact at tolerance 1e-7.
  CcdOptions tight;
  tight.tolerance = 1e-7;
  r = edgeEdgeCcd(p0, p1, q0, q1, zero, zero, Vector3d(0, 0, -0.499998), Vector3d(0, 0, -0.499998), tight);
  EXPECT_FALSE(r.hit);
  // Parabolic grazing: q descends then rises (rotating), touching at its lowest point. Emulated by moving q's
  // endpoints so that the coplanarity cubic has a double root: q tilts through the plane containing edge a.
  r = edgeEdgeCcd(p0, p1, Vector3d(0.5, -1, 0), Vector3d(0.5, 1, 0), zero, zero, Vector3d(-1, 0, 0),
                  Vector3d(-1, 0, 0));
  EXPECT_TRUE(r.hit);  // coplanar motion throughout: handled by sampling, first contact at t = 0
  EXPECT_NEAR(r.t, 0.0, 1e-12);
}

// Reference: earliest touching time by sampling the distance finely and bisecting the coplanarity cubic.
template <class Distance>
double sampledImpact(const Cubic& f, Distance&& distance, double tol) {
  constexpr int samples = 4000;
  for (int s = 0; s < samples; ++s) {
    double lo = double(s) / samples, hi = double(s + 1) / samples;
    if (std::abs(f(lo)) == 0.0 && distance(lo) <= tol) return lo;
    if ((f(lo) < 0) == (f(hi) < 0)) continue;
    for (int it = 0; it < 80; ++it) {
      const double mid = 0.5 * (lo + hi);
      ((f(mid) < 0) == (f(lo) < 0) ? lo : hi) = mid;
    }
    if (distance(lo) <= tol) return lo;
  }
  return -1.0;
}

TEST(CollisionCcdTest, RandomMotionsMatchSampling) {
  std::mt19937 rng(33);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto rv = [&] { return Vector3d(u(rng), u(rng), u(rng)); };
  int hits = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vector3d x[4] = {rv(), rv(), rv(), rv()};
    const Vector3d d[4] = {2 * rv(), 2 * rv(), 2 * rv(), 2 * rv()};
    CcdOptions options;
    options.tolerance = 1e-6;
    const bool edgeCase = trial % 2 == 1;
    CcdResult halley, newton;
    Cubic f;
    double reference;
    if (!edgeCase) {
      halley = vertexTriangleCcd(x[0], x[1], x[2], x[3], d[0], d[1], d[2], d[3], options);
      options.method = RootMethod::Newton;
      newton = vertexTriangleCcd(x[0], x[1], x[2], x[3], d[0], d[1], d[2], d[3], options);
      f = tripleProductCubic(x[2] - x[1], d[2] - d[1], x[3] - x[1], d[3] - d[1], x[0] - x[1], d[0] - d[1]);
      reference = sampledImpact(f, [&](double t) {
        return std::sqrt(closestPointTriangle(x[0] + t * d[0], x[1] + t * d[1], x[2] + t * d[2], x[3] + t * d[3])
                             .distanceSquared);
      }, 1e-6);
    } else {
      halley = edgeEdgeCcd(x[0], x[1], x[2], x[3], d[0], d[1], d[2], d[3], options);
      options.method = RootMethod::Newton;
      newton = edgeEdgeCcd(x[0], x[1], x[2], x[3], d[0], d[1], d[2], d[3], options);
      f = tripleProductCubic(x[1] - x[0], d[1] - d[0], x[2] - x[0], d[2] - d[0], x[3] - x[0], d[3] - d[0]);
      reference = sampledImpact(f, [&](double t) {
        return std::sqrt(closestPointsEdgeEdge(x[0] + t * d[0], x[1] + t * d[1], x[2] + t * d[2], x[3] + t * d[3])
                             .distanceSquared);
      }, 1e-6);
    }
    ASSERT_EQ(halley.hit, newton.hit) << trial;
    ASSERT_EQ(halley.hit, reference >= 0.0) << trial;
    if (halley.hit) {
      ++hits;
      EXPECT_NEAR(halley.t, newton.t, 1e-12);
      EXPECT_NEAR(halley.t, reference, 1e-9);
    }
  }
  EXPECT_GT(hits, 100);
}

}  // namespace
}  // namespace drape::collision
