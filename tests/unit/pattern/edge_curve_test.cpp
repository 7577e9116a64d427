// Edge geometry against independent values: closed-form quadratic Bezier length, fine polylines, circle
// arc length r * angle and arc midpoints, which side a curve bulges to, and even spacing by arc length.
#include "drape/pattern/edge_curve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace drape {
namespace {

using Eigen::Vector2d;

// A two-vertex panel whose edge 0 runs from a to b with the given curve (edge 1 closes it straight).
Panel onePanel(const Vector2d& a, const Vector2d& b, const EdgeCurve& curve) {
  Panel panel;
  panel.name = "test";
  panel.vertices = {a, b};
  PanelEdge e0;
  e0.start = 0;
  e0.end = 1;
  e0.curve = curve;
  PanelEdge e1;
  e1.start = 1;
  e1.end = 0;
  panel.edges = {e0, e1};
  return panel;
}

EdgeCurve quadratic(double x, double y) {
  EdgeCurve c;
  c.type = CurveType::Quadratic;
  c.controls = {Vector2d(x, y)};
  return c;
}

EdgeCurve cubic(Vector2d c1, Vector2d c2) {
  EdgeCurve c;
  c.type = CurveType::Cubic;
  c.controls = {c1, c2};
  return c;
}

EdgeCurve circle(double radius, bool largeArc, bool right) {
  EdgeCurve c;
  c.type = CurveType::Circle;
  c.radius = radius;
  c.largeArc = largeArc;
  c.right = right;
  return c;
}

// Length of the polyline through evaluateEdge at n + 1 parameter values.
double polylineLength(const Panel& panel, int edge, int n) {
  double length = 0.0;
  Vector2d prev = evaluateEdge(panel, edge, 0.0);
  for (int i = 1; i <= n; ++i) {
    const Vector2d p = evaluateEdge(panel, edge, double(i) / n);
    length += (p - prev).norm();
    prev = p;
  }
  return length;
}

// Closed form of the arc length of the quadratic Bezier p0, p1, p2: integral of sqrt(a t^2 + b t + c).
double quadraticBezierLength(const Vector2d& p0, const Vector2d& p1, const Vector2d& p2) {
  const Vector2d A = p0 - 2.0 * p1 + p2, B = p1 - p0;
  const double a = 4.0 * A.squaredNorm(), b = 8.0 * A.dot(B), c = 4.0 * B.squaredNorm();
  auto primitive = [&](double t) {
    const double q = a * t * t + b * t + c;
    return (2.0 * a * t + b) * std::sqrt(q) / (4.0 * a) +
           (4.0 * a * c - b * b) / (8.0 * std::pow(a, 1.5)) *
               std::log(std::abs(2.0 * std::sqrt(a) * std::sqrt(q) + 2.0 * a * t + b));
  };
  return primitive(1.0) - primitive(0.0);
}

TEST(EdgeCurve, StraightEdgeIsTheChord) {
  const Panel panel = onePanel({1, 2}, {4, 6}, EdgeCurve{});
  EXPECT_NEAR(edgeLength(panel, 0), 5.0, 1e-12);
  EXPECT_TRUE(evaluateEdge(panel, 0, 0.25).isApprox(Vector2d(1.75, 3.0), 1e-12));
  const auto samples = sampleEdge(panel, 0, 5);
  ASSERT_EQ(samples.size(), 6u);
  for (int i = 0; i <= 5; ++i) EXPECT_NEAR((samples[i] - Vector2d(1, 2)).norm(), i * 1.0, 1e-12);
}

TEST(EdgeCurve, QuadraticMatchesClosedFormAndBulgesLeftForPositiveY) {
  // Start (0,0), end (10,0): relative control (0.3, 0.4) is the absolute point (3, 4); left of +x is +y.
  const Panel panel = onePanel({0, 0}, {10, 0}, quadratic(0.3, 0.4));
  const Vector2d control(3, 4);
  EXPECT_TRUE(evaluateEdge(panel, 0, 0.5).isApprox(0.25 * Vector2d(0, 0) + 0.5 * control + 0.25 * Vector2d(10, 0)));
  EXPECT_GT(evaluateEdge(panel, 0, 0.5).y(), 0.0);
  const double exact = quadraticBezierLength({0, 0}, control, {10, 0});
  EXPECT_NEAR(edgeLength(panel, 0), exact, 1e-9 * exact);
  EXPECT_NEAR(edgeLength(panel, 0), polylineLength(panel, 0, 20000), 1e-7 * exact);

  // Negative y bulges right; on an edge running in -y direction "left" is +x.
  EXPECT_LT(evaluateEdge(onePanel({0, 0}, {10, 0}, quadratic(0.5, -0.2)), 0, 0.5).y(), 0.0);
  EXPECT_GT(evaluateEdge(onePanel({0, 10}, {0, 0}, quadratic(0.5, 0.2)), 0, 0.5).x(), 0.0);
}

TEST(EdgeCurve, CubicMatchesBernsteinFormAndFinePolyline) {
  const Vector2d a(2, 1), b(12, 5);
  const Panel panel = onePanel(a, b, cubic({0.2, 0.5}, {0.7, -0.6}));
  const Vector2d chord = b - a, left(-chord.y(), chord.x());
  const Vector2d c1 = a + 0.2 * chord + 0.5 * left, c2 = a + 0.7 * chord - 0.6 * left;
  EXPECT_TRUE(evaluateEdge(panel, 0, 0.5).isApprox((a + 3.0 * c1 + 3.0 * c2 + b) / 8.0, 1e-12));
  const double t = 0.3;
  const Vector2d bernstein =
      std::pow(1 - t, 3) * a + 3 * std::pow(1 - t, 2) * t * c1 + 3 * (1 - t) * t * t * c2 + t * t * t * b;
  EXPECT_TRUE(evaluateEdge(panel, 0, t).isApprox(bernstein, 1e-12));
  const double fine = polylineLength(panel, 0, 50000);
  EXPECT_NEAR(edgeLength(panel, 0), fine, 1e-7 * fine);
  EXPECT_GT(edgeLength(panel, 0), chord.norm());
}

TEST(EdgeCurve, CircleArcLengthMidpointAndSide) {
  const Vector2d a(0, 0), b(2, 0);
  // Radius 1 on a chord of 2: a half circle of length pi; right = true bulges to -y (right of +x).
  const Panel rightHalf = onePanel(a, b, circle(1.0, false, true));
  EXPECT_NEAR(edgeLength(rightHalf, 0), std::numbers::pi, 1e-12);
  EXPECT_TRUE(evaluateEdge(rightHalf, 0, 0.5).isApprox(Vector2d(1, -1), 1e-12));
  const Panel leftHalf = onePanel(a, b, circle(1.0, false, false));
  EXPECT_TRUE(evaluateEdge(leftHalf, 0, 0.5).isApprox(Vector2d(1, 1), 1e-12));

  // Radius 2: the small arc spans 2 asin(1/2) = pi/3, the large one 2 pi - pi/3; sagitta r -+ sqrt(r^2 - 1).
  const double r = 2.0, small = 2.0 * std::asin(0.5);
  const Panel smallRight = onePanel(a, b, circle(r, false, true));
  EXPECT_NEAR(edgeLength(smallRight, 0), r * small, 1e-12);
  EXPECT_NEAR(evaluateEdge(smallRight, 0, 0.5).y(), -(r - std::sqrt(3.0)), 1e-12);
  EXPECT_NEAR(evaluateEdge(smallRight, 0, 0.5).x(), 1.0, 1e-12);
  const Panel largeRight = onePanel(a, b, circle(r, true, true));
  EXPECT_NEAR(edgeLength(largeRight, 0), r * (2.0 * std::numbers::pi - small), 1e-12);
  EXPECT_NEAR(evaluateEdge(largeRight, 0, 0.5).y(), -(r + std::sqrt(3.0)), 1e-12);
  const Panel largeLeft = onePanel(a, b, circle(r, true, false));
  EXPECT_NEAR(evaluateEdge(largeLeft, 0, 0.5).y(), r + std::sqrt(3.0), 1e-12);

  // Every sample of the small right arc is at distance r from its centre (1, sqrt(3)).
  for (const Vector2d& p : sampleEdge(smallRight, 0, 16))
    EXPECT_NEAR((p - Vector2d(1, std::sqrt(3.0))).norm(), r, 1e-12);
  EXPECT_NEAR(polylineLength(largeRight, 0, 100000), edgeLength(largeRight, 0), 1e-6);
}

TEST(EdgeCurve, SamplesAreEvenlySpacedByArcLength) {
  // A strongly curved cubic (speed varies a lot along t), checked against a dense independent polyline.
  const Panel panel = onePanel({0, 0}, {10, 0}, cubic({0.05, 0.8}, {1.2, 0.3}));
  const int segments = 20;
  const auto samples = sampleEdge(panel, 0, segments);
  ASSERT_EQ(samples.size(), size_t(segments + 1));
  EXPECT_TRUE(samples.front().isApprox(Vector2d(0, 0)));
  EXPECT_TRUE(samples.back().isApprox(Vector2d(10, 0)));

  const int dense = 100000;
  std::vector<Vector2d> points(dense + 1);
  std::vector<double> arc(dense + 1, 0.0);
  for (int i = 0; i <= dense; ++i) {
    points[i] = evaluateEdge(panel, 0, double(i) / dense);
    if (i > 0) arc[i] = arc[i - 1] + (points[i] - points[i - 1]).norm();
  }
  const double total = arc.back();
  EXPECT_NEAR(edgeLength(panel, 0), total, 1e-6 * total);
  // The arc length at each sample (taken at the nearest dense point) is k / segments of the total.
  size_t cursor = 0;
  for (int k = 0; k <= segments; ++k) {
    size_t best = cursor;
    for (size_t i = cursor; i < points.size(); ++i)
      if ((points[i] - samples[k]).squaredNorm() < (points[best] - samples[k]).squaredNorm()) best = i;
    EXPECT_NEAR(arc[best], total * k / segments, 2e-4 * total) << "sample " << k;
    cursor = best;
  }
  // Chords between neighbours are nearly equal too (the curve is smooth at this resolution).
  double minChord = 1e300, maxChord = 0.0;
  for (int k = 0; k < segments; ++k) {
    const double chord = (samples[k + 1] - samples[k]).norm();
    minChord = std::min(minChord, chord);
    maxChord = std::max(maxChord, chord);
  }
  EXPECT_LT(maxChord / minChord, 1.02);
}

TEST(EdgeCurve, PanelOutlineRespectsMaxSegmentAndHasNoRepeatedPoints) {
  // Square 0..20 with the top edge (running -x) a half circle of radius 10 bulging up (right of -x is +y).
  Panel panel;
  panel.vertices = {{0, 0}, {20, 0}, {20, 20}, {0, 20}};
  for (int i = 0; i < 4; ++i) {
    PanelEdge e;
    e.start = i;
    e.end = (i + 1) % 4;
    panel.edges.push_back(e);
  }
  panel.edges[2].curve = circle(10.0, false, true);
  const double maxSegment = 0.5;
  const auto outline = panelOutline(panel, maxSegment);
  double twiceArea = 0.0;
  for (size_t i = 0; i < outline.size(); ++i) {
    const Vector2d& p = outline[i];
    const Vector2d& q = outline[(i + 1) % outline.size()];
    EXPECT_LE((q - p).norm(), maxSegment + 1e-9);
    EXPECT_GT((q - p).norm(), 1e-6) << "repeated point at " << i;
    twiceArea += p.x() * q.y() - p.y() * q.x();
  }
  const double exactArea = 400.0 + 0.5 * std::numbers::pi * 100.0;
  EXPECT_NEAR(0.5 * twiceArea, exactArea, 0.01 * exactArea);
  EXPECT_GT(0.5 * twiceArea, 400.0 + 0.5 * std::numbers::pi * 100.0 * 0.99);  // bulges outward, adds area
}

}  // namespace
}  // namespace drape
