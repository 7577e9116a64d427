// meshPanel on simple outlines: area, boundary, orientation, topology and
// quality checks computed independently of the mesher from the output arrays.
#include "drape/garment/panel_mesher.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <numbers>
#include <set>

#include "drape/core/input_error.h"

namespace drape {
namespace {

using Outline = std::vector<Eigen::Vector2d>;

// The corners joined by straight segments, each cut into max(1, round(length /
// spacing)) equal pieces.
Outline sampleCorners(const Outline& corners, double spacing) {
  Outline out;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector2d a = corners[i];
    const Eigen::Vector2d b = corners[(i + 1) % corners.size()];
    const int segments = std::max(1, static_cast<int>(std::lround((b - a).norm() / spacing)));
    for (int k = 0; k < segments; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / segments));
  }
  return out;
}

Outline circle(double radius, int points) {
  Outline out;
  for (int i = 0; i < points; ++i) {
    const double a = 2.0 * std::numbers::pi * i / points;
    out.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  return out;
}

double polygonArea(const Outline& b) {
  double twice = 0.0;
  for (size_t i = 0; i < b.size(); ++i) {
    const auto& p = b[i];
    const auto& q = b[(i + 1) % b.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice;
}

double triangleArea(const PanelMesh& m, int t) {
  const Eigen::Vector2d a = m.vertices.row(m.triangles(t, 0));
  const Eigen::Vector2d b = m.vertices.row(m.triangles(t, 1));
  const Eigen::Vector2d c = m.vertices.row(m.triangles(t, 2));
  const Eigen::Vector2d u = b - a, v = c - a;
  return 0.5 * (u.x() * v.y() - u.y() * v.x());
}

// Smallest interior angle of triangle t, degrees.
double minAngleDeg(const PanelMesh& m, int t) {
  double best = 180.0;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d p = m.vertices.row(m.triangles(t, k));
    const Eigen::Vector2d q = m.vertices.row(m.triangles(t, (k + 1) % 3));
    const Eigen::Vector2d r = m.vertices.row(m.triangles(t, (k + 2) % 3));
    const Eigen::Vector2d u = (q - p).normalized(), v = (r - p).normalized();
    best = std::min(best, std::acos(std::clamp(u.dot(v), -1.0, 1.0)) * 180.0 / std::numbers::pi);
  }
  return best;
}

// Interior angle of the outline at each point, degrees (outline made
// counter-clockwise first).
std::vector<double> outlineAnglesDeg(const Outline& b) {
  const double sign = polygonArea(b) > 0 ? 1.0 : -1.0;
  std::vector<double> angles(b.size());
  for (size_t i = 0; i < b.size(); ++i) {
    const Eigen::Vector2d prev = b[(i + b.size() - 1) % b.size()], next = b[(i + 1) % b.size()];
    const Eigen::Vector2d u = next - b[i], v = prev - b[i];
    double a = std::atan2(sign * (u.x() * v.y() - u.y() * v.x()), u.dot(v));
    if (a < 0) a += 2.0 * std::numbers::pi;
    angles[i] = a * 180.0 / std::numbers::pi;
  }
  return angles;
}

struct Quality {
  double minAngle = 180.0;         // over triangles not excused (see checkMesh)
  double minInteriorEdge = 1e300;  // over edges not on the boundary
  double maxInteriorEdge = 0.0;
  int excused = 0;
};

// Every property meshPanel promises, checked from the arrays. Returns the
// quality statistics.
Quality checkMesh(const Outline& boundary, const PanelMesh& m) {
  const int n = static_cast<int>(boundary.size());
  Quality q;
  EXPECT_GE(m.vertices.rows(), n);
  // Boundary preserved bit for bit, in order.
  for (int i = 0; i < n && i < m.vertices.rows(); ++i) {
    EXPECT_EQ(m.vertices(i, 0), boundary[i].x()) << "boundary point " << i;
    EXPECT_EQ(m.vertices(i, 1), boundary[i].y()) << "boundary point " << i;
  }
  // CCW with positive area; area conserved.
  double sum = 0.0;
  for (int t = 0; t < m.triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(m.triangles(t, k), 0);
      EXPECT_LT(m.triangles(t, k), m.vertices.rows());
    }
    const double a = triangleArea(m, t);
    EXPECT_GT(a, 0.0) << "triangle " << t;
    sum += a;
  }
  const double area = std::abs(polygonArea(boundary));
  EXPECT_NEAR(sum, area, 1e-9 * area);

  // Edge -> number of incident triangles; boundary edges (one triangle) must be
  // the input segments.
  std::map<std::pair<int, int>, int> edgeUse;
  std::set<int> used;
  for (int t = 0; t < m.triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles(t, k), b = m.triangles(t, (k + 1) % 3);
      ++edgeUse[{std::min(a, b), std::max(a, b)}];
      used.insert(a);
    }
  }
  EXPECT_EQ(static_cast<int>(used.size()), m.vertices.rows()) << "unreferenced vertices";
  std::set<std::pair<int, int>> inputEdges;
  for (int i = 0; i < n; ++i) inputEdges.insert({std::min(i, (i + 1) % n), std::max(i, (i + 1) % n)});
  int boundaryEdges = 0;
  for (const auto& [e, count] : edgeUse) {
    EXPECT_LE(count, 2) << "non-manifold edge " << e.first << "-" << e.second;
    if (count == 1) {
      ++boundaryEdges;
      EXPECT_TRUE(inputEdges.count(e)) << "mesh boundary edge " << e.first << "-" << e.second
                                       << " is not a segment of the input boundary";
    }
  }
  EXPECT_EQ(boundaryEdges, n);
  // Euler characteristic of a disk: V - E + F = 1.
  EXPECT_EQ(m.vertices.rows() - static_cast<long>(edgeUse.size()) + m.triangles.rows(), 1);

  // Quality. Excused: triangles at an outline corner sharper than 20 degrees,
  // and triangles whose three vertices all lie on the fixed boundary (the
  // mesher may not split boundary segments to improve them). Interior edges are
  // the non-boundary edges of the remaining triangles.
  const std::vector<double> corner = outlineAnglesDeg(boundary);
  for (int t = 0; t < m.triangles.rows(); ++t) {
    bool sharp = false;
    int onBoundary = 0;
    for (int k = 0; k < 3; ++k) {
      const int v = m.triangles(t, k);
      if (v < n) {
        ++onBoundary;
        sharp = sharp || corner[v] < 20.0;
      }
    }
    if (sharp || onBoundary == 3) {
      ++q.excused;
      continue;
    }
    q.minAngle = std::min(q.minAngle, minAngleDeg(m, t));
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles(t, k), b = m.triangles(t, (k + 1) % 3);
      if (edgeUse[{std::min(a, b), std::max(a, b)}] != 2) continue;  // boundary segment: fixed by the input
      const double len = (m.vertices.row(a) - m.vertices.row(b)).norm();
      q.minInteriorEdge = std::min(q.minInteriorEdge, len);
      q.maxInteriorEdge = std::max(q.maxInteriorEdge, len);
    }
  }
  std::cout << "  V " << m.vertices.rows() << " F " << m.triangles.rows() << " excused " << q.excused << " min angle "
            << q.minAngle << " interior edges [" << q.minInteriorEdge << ", " << q.maxInteriorEdge << "]\n";
  return q;
}

void expectQuality(const Quality& q, double target) {
  EXPECT_GE(q.minAngle, 20.0);
  EXPECT_LE(q.maxInteriorEdge, 2.0 * target);
  EXPECT_GE(q.minInteriorEdge, 0.5 * target);
}

TEST(PanelMesher, Square) {
  const double h = 0.05;
  const Outline b = sampleCorners({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, h);
  const PanelMesh m = meshPanel(b, h, "square");
  const Quality q = checkMesh(b, m);
  expectQuality(q, h);
  // An equilateral-ish mesh of a unit square at h = 0.05 has on the order of 1
  // / (0.433 h^2) = 924 triangles.
  EXPECT_GT(m.triangles.rows(), 400);
  EXPECT_LT(m.triangles.rows(), 1400);
}

TEST(PanelMesher, ClockwiseSquareGivesCounterClockwiseTriangles) {
  const double h = 0.1;
  Outline b = sampleCorners({{0, 0}, {0, 1}, {1, 1}, {1, 0}}, h);  // clockwise
  const PanelMesh m = meshPanel(b, h, "cw");
  expectQuality(checkMesh(b, m), h);
}

TEST(PanelMesher, Disc) {
  const double h = 0.05;
  const Outline b = circle(1.0, static_cast<int>(std::lround(2.0 * std::numbers::pi / h)));
  const PanelMesh m = meshPanel(b, h, "disc");
  expectQuality(checkMesh(b, m), h);
}

TEST(PanelMesher, LShape) {
  const double h = 0.04;
  const Outline b = sampleCorners({{0, 0}, {1, 0}, {1, 0.4}, {0.4, 0.4}, {0.4, 1}, {0, 1}}, h);
  const PanelMesh m = meshPanel(b, h, "L");
  expectQuality(checkMesh(b, m), h);
}

TEST(PanelMesher, ThinSliver) {
  // 1 x 0.02 strip at target 0.05: no room for interior points; every triangle
  // has 3 boundary vertices.
  const double h = 0.05;
  const Outline b = sampleCorners({{0, 0}, {1, 0}, {1, 0.02}, {0, 0.02}}, h);
  const PanelMesh m = meshPanel(b, h, "sliver");
  checkMesh(b, m);
  EXPECT_EQ(m.vertices.rows(), static_cast<Eigen::Index>(b.size()));
  EXPECT_EQ(m.triangles.rows(), static_cast<Eigen::Index>(b.size()) - 2);
}

TEST(PanelMesher, SharpCorner) {
  // A 10 degree wedge with a round-ish end: the tip forces small angles, the
  // rest must be good.
  const double h = 0.03;
  const double half = 5.0 * std::numbers::pi / 180.0;
  Outline corners = {{0, 0}};
  for (int i = 0; i <= 8; ++i) {
    const double a = -half + 2.0 * half * i / 8.0;
    corners.emplace_back(1.0 * std::cos(a), 1.0 * std::sin(a));
  }
  const Outline b = sampleCorners(corners, h);
  const PanelMesh m = meshPanel(b, h, "wedge");
  const Quality q = checkMesh(b, m);
  EXPECT_GT(q.excused, 0);
  expectQuality(q, h);
}

TEST(PanelMesher, VerySharpCornerAndCoarseBoundaryTerminate) {
  // A 1 degree wedge, and a square given by its 4 corners only with a target
  // 100 times smaller: the mesher may not split the boundary, so it cannot
  // reach the target, but it must stop with a valid mesh.
  const double half = 0.5 * std::numbers::pi / 180.0;
  const Outline wedge =
      sampleCorners({{0, 0}, {std::cos(half), -std::sin(half)}, {std::cos(half), std::sin(half)}}, 0.01);
  checkMesh(wedge, meshPanel(wedge, 0.01, "wedge"));
  const Outline square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const PanelMesh m = meshPanel(square, 0.01, "coarse");
  checkMesh(square, m);
}

TEST(PanelMesher, NearlyCollinearBoundaryPoints) {
  // Points along the bottom edge jitter by 1e-12: nearly collinear, still a
  // simple polygon.
  const double h = 0.1;
  Outline b = sampleCorners({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, h);
  for (size_t i = 1; i < 10; ++i) b[i].y() = (i % 2 ? 1e-12 : -1e-12);
  const PanelMesh m = meshPanel(b, h, "jitter");
  checkMesh(b, m);
}

TEST(PanelMesher, RejectsBadBoundaries) {
  auto message = [](const Outline& b, double h) {
    try {
      meshPanel(b, h, "shirt.json: panel 'front'");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({{0, 0}, {1, 0}}, 0.1).rfind("shirt.json: panel 'front': ", 0), 0u);
  EXPECT_NE(message({{0, 0}, {1, 0}}, 0.1).find("at least 3"), std::string::npos);
  EXPECT_NE(message({{0, 0}, {1, 0}, {2, 0}}, 0.1).find("zero area"), std::string::npos);
  // Bow tie.
  EXPECT_NE(message({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, 0.1).find("self-intersecting"), std::string::npos);
  // Outline touching itself at a point (coincident points).
  EXPECT_NE(message({{0, 0}, {1, 0}, {0.5, 0.5}, {1, 1}, {0, 1}, {0.5, 0.5}}, 0.1).find("self-intersecting"),
            std::string::npos);
  // Too fine: about 4.6e8 triangles for a 1 m square at 0.05 mm.
  const std::string tooFine = message({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 5e-5);
  EXPECT_NE(tooFine.find("limit"), std::string::npos) << tooFine;
  EXPECT_NE(message({{0, 0}, {1, 0}, {1, 1}}, 0.0).find("target edge length"), std::string::npos);
  EXPECT_NE(message({{0, 0}, {1, 0}, {1, NAN}}, 0.1).find("not finite"), std::string::npos);
}

// Inserted points are numbered along a Hilbert curve and triangles sorted along it: the vertices of a triangle
// are close in the numbering (the solvers' assembly is memory bound). Measured as the median over the interior
// triangles of the vertex-index span, against the vertex count: CGAL's own order gives about half the count.
TEST(PanelMesher, InteriorNumberingIsLocal) {
  const double h = 0.01;
  const Outline b = sampleCorners({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, h);
  const PanelMesh m = meshPanel(b, h, "square");
  checkMesh(b, m);
  const int boundary = static_cast<int>(b.size());
  std::vector<int> spans, centroidJumps;
  for (Eigen::Index t = 0; t < m.triangles.rows(); ++t) {
    const Eigen::Vector3i tri = m.triangles.row(t).transpose();
    if (tri.minCoeff() < boundary) continue;
    spans.push_back(tri.maxCoeff() - tri.minCoeff());
  }
  ASSERT_GT(spans.size(), 10000u);
  std::nth_element(spans.begin(), spans.begin() + spans.size() / 2, spans.end());
  const double median = spans[spans.size() / 2];
  EXPECT_LT(median, 0.02 * m.vertices.rows()) << "median span " << median << " of " << m.vertices.rows();
  // Consecutive triangles are neighbours in the plane: the mean centroid step is a few edge lengths.
  double step = 0.0;
  auto centroid = [&](Eigen::Index t) {
    return (m.vertices.row(m.triangles(t, 0)) + m.vertices.row(m.triangles(t, 1)) + m.vertices.row(m.triangles(t, 2))) / 3.0;
  };
  for (Eigen::Index t = 1; t < m.triangles.rows(); ++t) step += (centroid(t) - centroid(t - 1)).norm();
  step /= static_cast<double>(m.triangles.rows() - 1);
  EXPECT_LT(step, 3.0 * h) << "mean centroid step " << step;
}

}  // namespace
}  // namespace drape
