// Loading real GarmentCode patterns (../shared/data) and small patterns of our own (tests/data/patterns):
// structure, panel order, units, and that every curved edge bends the way its designers drew it.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "drape/core/input_error.h"
#include "drape/pattern/edge_curve.h"
#include "drape/pattern/pattern_loader.h"
#include "shared_data.h"

namespace drape {
namespace {

using Eigen::Vector2d;

double cross(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

double polygonArea(const std::vector<Vector2d>& p) {
  double twice = 0.0;
  for (size_t i = 0; i < p.size(); ++i) twice += cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * twice;
}

// Brute force, independent of the loader's sweep: do two non-adjacent segments of the closed polyline meet?
bool selfIntersects(const std::vector<Vector2d>& p) {
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the wrap
      const Vector2d &a = p[i], &b = p[(i + 1) % n], &c = p[j], &d = p[(j + 1) % n];
      const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
      const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
      if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0) return true;
    }
  }
  return false;
}

// Even-odd point-in-polygon.
bool inside(const std::vector<Vector2d>& poly, const Vector2d& q) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if ((poly[i].y() > q.y()) != (poly[j].y() > q.y()) &&
        q.x() < (poly[j].x() - poly[i].x()) * (q.y() - poly[i].y()) / (poly[j].y() - poly[i].y()) + poly[i].x())
      in = !in;
  }
  return in;
}

std::vector<Vector2d> corners(const Panel& panel) {
  std::vector<Vector2d> out;
  for (const PanelEdge& e : panel.edges) out.push_back(panel.vertices[e.start]);
  return out;
}

const Panel& panelNamed(const Pattern& pattern, const std::string& name) {
  const int i = pattern.panelIndex(name);
  EXPECT_GE(i, 0) << name;
  return pattern.panels.at(std::max(i, 0));
}

// Midpoint (by parameter) of an edge lies inside the polygon of the panel's corners: the edge curves inward.
bool curvesInward(const Panel& panel, int edge) { return inside(corners(panel), evaluateEdge(panel, edge, 0.5)); }

class PatternRealFiles : public ::testing::TestWithParam<const char*> {};

TEST_P(PatternRealFiles, LoadsWithSimpleOutlinesOfSaneArea) {
  DRAPE_SHARED_FILE(file, GetParam());
  Diagnostics diagnostics;
  const Pattern pattern = loadPattern(file, &diagnostics);
  for (const auto& w : diagnostics.warnings()) std::cout << "  warning: " << w << "\n";
  ASSERT_FALSE(pattern.panels.empty());
  EXPECT_NE(pattern.source.find(file.filename().string()), std::string::npos);
  for (const Panel& panel : pattern.panels) {
    SCOPED_TRACE(panel.name);
    const std::vector<Vector2d> outline = panelOutline(panel, 0.25);
    EXPECT_FALSE(selfIntersects(outline));
    const double cornerArea = polygonArea(corners(panel));
    const double area = polygonArea(outline);
    ASSERT_GT(std::abs(cornerArea), 1.0);
    const double ratio = area / cornerArea;  // > 0: same orientation
    EXPECT_GT(ratio, 0.8);
    EXPECT_LT(ratio, 1.25);
  }
}

INSTANTIATE_TEST_SUITE_P(All, PatternRealFiles,
                         ::testing::Values("garmentcode/shirt_mean_specification.json",
                                           "garmentcode/dress_pencil_specification.json",
                                           "garment-pattern-generator/tee.json",
                                           "garment-pattern-generator/skirt_2_panels.json"));

}  // namespace
}  // namespace drape
