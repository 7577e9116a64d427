// Loading real GarmentCode patterns (../shared/data) and small patterns of our own (tests/data/patterns):
// structure, panel order, units, and that every curved edge bends the way its designers drew it.
#include "drape/pattern/pattern_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "drape/core/input_error.h"
#include "drape/pattern/edge_curve.h"
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

// The designers' intent, checked against the corner polygon: armholes and necklines curve into the panel,
// sleeve caps and flared hems bulge out of it. A flipped sign convention fails every line below.
TEST(PatternSignConvention, ShirtCurvesBendTheWayTheyWereDrawn) {
  DRAPE_SHARED_FILE(file, "garmentcode/shirt_mean_specification.json");
  const Pattern p = loadPattern(file);
  EXPECT_TRUE(curvesInward(panelNamed(p, "left_ftorso"), 3));      // armhole
  EXPECT_TRUE(curvesInward(panelNamed(p, "left_ftorso"), 5));      // front neckline
  EXPECT_TRUE(curvesInward(panelNamed(p, "right_ftorso"), 3));     // armhole (mirrored)
  EXPECT_TRUE(curvesInward(panelNamed(p, "right_ftorso"), 1));     // neckline (mirrored)
  EXPECT_TRUE(curvesInward(panelNamed(p, "left_btorso"), 4));      // back armhole
  EXPECT_FALSE(curvesInward(panelNamed(p, "left_sleeve_f"), 1));   // sleeve cap
  EXPECT_FALSE(curvesInward(panelNamed(p, "right_sleeve_f"), 2));  // sleeve cap (mirrored)
  EXPECT_FALSE(curvesInward(panelNamed(p, "left_sleeve_b"), 3));   // back sleeve cap
}

TEST(PatternSignConvention, LegacyTeeAndSkirtCurvesBendTheWayTheyWereDrawn) {
  DRAPE_SHARED_FILE(tee, "garment-pattern-generator/tee.json");
  DRAPE_SHARED_FILE(skirt, "garment-pattern-generator/skirt_2_panels.json");
  const Pattern t = loadPattern(tee);
  EXPECT_TRUE(curvesInward(panelNamed(t, "front"), 2));      // armhole
  EXPECT_TRUE(curvesInward(panelNamed(t, "front"), 6));      // armhole (other side)
  EXPECT_TRUE(curvesInward(panelNamed(t, "back"), 0));       // back neckline (a clockwise loop: sign still holds)
  EXPECT_TRUE(curvesInward(panelNamed(t, "back"), 2));       // back armhole
  EXPECT_FALSE(curvesInward(panelNamed(t, "lfsleeve"), 2));  // sleeve cap
  EXPECT_FALSE(curvesInward(panelNamed(t, "rbsleeve"), 2));  // sleeve cap
  const Pattern s = loadPattern(skirt);
  EXPECT_FALSE(curvesInward(panelNamed(s, "front"), 0));  // hem bulges down
  EXPECT_TRUE(curvesInward(panelNamed(s, "front"), 3));   // waist dips down into the panel
}

TEST(PatternLoader, ShirtStructureOrderAndUnits) {
  DRAPE_SHARED_FILE(file, "garmentcode/shirt_mean_specification.json");
  Diagnostics diagnostics;
  const Pattern p = loadPattern(file, &diagnostics);
  EXPECT_TRUE(diagnostics.warnings().empty());
  EXPECT_EQ(p.unitsInMeter, 100.0);
  const std::vector<std::string> order = {"right_sleeve_b", "right_sleeve_f", "right_btorso",  "right_ftorso",
                                          "left_btorso",    "left_ftorso",    "left_sleeve_b", "left_sleeve_f"};
  ASSERT_EQ(p.panels.size(), order.size());
  for (size_t i = 0; i < order.size(); ++i) EXPECT_EQ(p.panels[i].name, order[i]);
  EXPECT_EQ(p.stitches.size(), 18u);
  const Panel& sleeve = panelNamed(p, "left_sleeve_f");
  EXPECT_NEAR(sleeve.translation.x(), 53.57347770869189, 1e-12);
  EXPECT_NEAR(sleeve.rotationDeg.z(), -50.48299999999997, 1e-12);
  EXPECT_EQ(sleeve.edges[1].curve.type, CurveType::Cubic);
  EXPECT_NEAR(sleeve.edges[1].curve.controls[0].y(), -0.1498416610988617, 1e-15);
  // First stitch: left_sleeve_f edge 0 with left_sleeve_b edge 5, indices into the ordered panels.
  EXPECT_EQ(p.panels[p.stitches[0].a.panel].name, "left_sleeve_f");
  EXPECT_EQ(p.stitches[0].a.edge, 0);
  EXPECT_EQ(p.panels[p.stitches[0].b.panel].name, "left_sleeve_b");
  EXPECT_EQ(p.stitches[0].b.edge, 5);
  // Every stitch of the shirt joins edges of equal length (to 5%).
  for (const Stitch& s : p.stitches) {
    const double la = edgeLength(p.panels[s.a.panel], s.a.edge), lb = edgeLength(p.panels[s.b.panel], s.b.edge);
    EXPECT_NEAR(la, lb, 0.05 * std::max(la, lb));
  }
}

TEST(PatternLoader, DressWaistStitchesWarnWithBothEdgesAndLengths) {
  DRAPE_SHARED_FILE(file, "garmentcode/dress_pencil_specification.json");
  Diagnostics diagnostics;
  const Pattern p = loadPattern(file, &diagnostics);
  EXPECT_EQ(p.panels.front().name, "right_btorso");
  EXPECT_EQ(panelNamed(p, "skirt_back").label, "leg");
  EXPECT_EQ(panelNamed(p, "skirt_back").edges[3].label, "lower_interface");
  // The bodice waist is 23% longer than the skirt waist it is sewn to (GarmentCode gathers it): 9 warnings.
  ASSERT_EQ(diagnostics.warnings().size(), 9u);
  const std::string& w = diagnostics.warnings().front();
  for (const char* part : {"dress_pencil_specification.json: stitch 14", "panel 'right_ftorso' edge 5", "28.69",
                           "panel 'skirt_front' edge 6", "22.03", "23.2%"})
    EXPECT_NE(w.find(part), std::string::npos) << part << " in " << w;
}

TEST(PatternLoader, LegacyTeeKeepsFileOrderAndItsUnits) {
  DRAPE_SHARED_FILE(file, "garment-pattern-generator/tee.json");
  const Pattern p = loadPattern(file);
  EXPECT_EQ(p.unitsInMeter, 300.0);
  const std::vector<std::string> order = {"lfsleeve", "back", "lbsleeve", "rfsleeve", "rbsleeve", "front"};
  ASSERT_EQ(p.panels.size(), order.size());
  for (size_t i = 0; i < order.size(); ++i) EXPECT_EQ(p.panels[i].name, order[i]);
  EXPECT_EQ(p.stitches.size(), 12u);
  const Panel& sleeve = panelNamed(p, "lfsleeve");
  EXPECT_EQ(sleeve.edges[2].curve.type, CurveType::Quadratic);
  EXPECT_EQ(sleeve.edges[2].curve.controls[0], Eigen::Vector2d(0.7, -0.4));
  EXPECT_EQ(sleeve.rotationDeg, Eigen::Vector3d(180, 180, 0));
}

TEST(PatternLoader, CirclePatchWithTwoVertexLensAndRightWrongStitch) {
  Diagnostics diagnostics;
  const Pattern p = loadPattern(test::testDataDir() / "patterns" / "circle_patch.json", &diagnostics);
  EXPECT_TRUE(diagnostics.warnings().empty());
  ASSERT_EQ(p.panels.size(), 2u);
  EXPECT_EQ(p.panels[0].name, "lens");  // panel_order, not file order
  const Panel& patch = p.panels[1];
  EXPECT_EQ(patch.label, "patch_label");
  EXPECT_EQ(patch.edges[0].label, "bottom");
  EXPECT_EQ(patch.edges[2].curve.type, CurveType::Circle);
  EXPECT_TRUE(patch.edges[2].curve.right);
  EXPECT_FALSE(patch.edges[2].curve.largeArc);
  EXPECT_NEAR(edgeLength(patch, 2), 10.0 * std::numbers::pi, 1e-9);
  EXPECT_TRUE(evaluateEdge(patch, 2, 0.5).isApprox(Eigen::Vector2d(10, 30), 1e-12));  // dome bulges up
  const Panel& lens = p.panels[0];  // two arcs of radius 5: a full circle, flags given as 0/1
  EXPECT_NEAR(std::abs(polygonArea(panelOutline(lens, 0.05))), 25.0 * std::numbers::pi, 0.01);
  ASSERT_EQ(p.stitches.size(), 1u);
  EXPECT_TRUE(p.stitches[0].rightWrong);
  EXPECT_EQ(p.stitches[0].a.panel, 1);
  EXPECT_EQ(p.stitches[0].b.edge, 3);
}

TEST(PatternLoader, AbsoluteCurvatureCoordinatesBecomeRelative) {
  const Pattern p = loadPattern(test::testDataDir() / "patterns" / "absolute_curves.json");
  EXPECT_EQ(p.unitsInMeter, 1000.0);
  const Panel& panel = p.panels.at(0);
  EXPECT_TRUE(panel.edges[0].curve.controls[0].isApprox(Eigen::Vector2d(0.5, -0.25), 1e-12));
  EXPECT_TRUE(panel.edges[1].curve.controls[0].isApprox(Eigen::Vector2d(0.25, -0.1), 1e-12));
  EXPECT_TRUE(panel.edges[1].curve.controls[1].isApprox(Eigen::Vector2d(0.75, 0.1), 1e-12));
  // The quadratic through absolute control (10, -5) has its midpoint at (10, -2.5).
  EXPECT_TRUE(evaluateEdge(panel, 0, 0.5).isApprox(Eigen::Vector2d(10, -2.5), 1e-12));
}

TEST(PatternLoader, LegacyCurvatureAndFileOrderWithoutPanelOrder) {
  Diagnostics diagnostics;
  const Pattern p = loadPattern(test::testDataDir() / "patterns" / "legacy_file_order.json", &diagnostics);
  ASSERT_EQ(p.panels.size(), 2u);
  EXPECT_EQ(p.panels[0].name, "zeta");  // file order, not alphabetical
  EXPECT_EQ(p.panels[1].name, "alpha");
  EXPECT_TRUE(diagnostics.warnings().empty());  // the curved hem is within 5% of the straight one
}

TEST(PatternLoader, MismatchedStitchWarnsNamingBothEdgesAndLengths) {
  Diagnostics diagnostics;
  loadPattern(test::testDataDir() / "patterns" / "mismatched_stitch.json", &diagnostics);
  ASSERT_EQ(diagnostics.warnings().size(), 1u);
  const std::string& w = diagnostics.warnings()[0];
  for (const char* part : {"mismatched_stitch.json: stitch 0", "panel 'short' edge 0 (length 20)",
                           "panel 'long' edge 1 (length 30)", "33.3%"})
    EXPECT_NE(w.find(part), std::string::npos) << part << " in " << w;
}

TEST(PatternLoader, ParsePatternUsesTheGivenSourceName) {
  const std::string text = R"({"pattern": {"panels": {"p": {"vertices": [[0,0],[1,0],[0,1]],
    "edges": [{"endpoints": [0,1]}, {"endpoints": [1,2]}, {"endpoints": [2,5]}],
    "translation": [0,0,0], "rotation": [0,0,0]}}, "stitches": []}, "properties": {"units_in_meter": 100}})";
  try {
    parsePattern(text, "memory.json");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "memory.json: panel 'p' edge 2: endpoint 5 out of range (panel has 3 vertices)");
  }
}

}  // namespace
}  // namespace drape
