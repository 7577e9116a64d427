// buildGarment on patterns built in code (straight edges): sampling counts,
// units, placement, edge vertex lists and stitch pairing, checked against hand
// computations.
#include "drape/garment/garment_builder.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "drape/core/input_error.h"

namespace drape {
namespace {

// A rectangle panel w x h (file units) with corners (0,0), (w,0), (w,h), (0,h),
// edges 0..3 counter-clockwise.
Panel rectangle(const std::string& name, double w, double h) {
  Panel p;
  p.name = name;
  p.vertices = {{0, 0}, {w, 0}, {w, h}, {0, h}};
  for (int e = 0; e < 4; ++e) p.edges.push_back(PanelEdge{e, (e + 1) % 4, {}, ""});
  return p;
}

// Front: 50 x 60 cm at z = +10. Back: same size turned 180 degrees about y, so
// that its local x runs towards -x in the world, translated to x = 50, z = -10:
// the front's right edge 1 (bottom -> top) lies over the back's left edge 3
// (top -> bottom) and the two side seams are 20 cm apart in z.
Pattern frontBack() {
  Pattern pattern;
  pattern.source = "test.json";
  pattern.unitsInMeter = 100.0;
  Panel front = rectangle("front", 50, 60);
  front.translation = {0, 0, 10};
  Panel back = rectangle("back", 50, 60);
  back.translation = {50, 0, -10};
  back.rotationDeg = {0, 180, 0};
  pattern.panels = {front, back};
  pattern.stitches.push_back(Stitch{{0, 1}, {1, 3}, false});  // right side seam
  pattern.stitches.push_back(Stitch{{0, 3}, {1, 1}, false});  // left side seam
  return pattern;
}

double meshArea(const Garment& g, int panel) {
  double area = 0.0;
  for (int t = 0; t < g.triangleCount(); ++t) {
    if (g.trianglePanel(t) != panel) continue;
    const Eigen::Vector2d a = g.rest.row(g.triangles(t, 0)), b = g.rest.row(g.triangles(t, 1)),
                          c = g.rest.row(g.triangles(t, 2));
    const Eigen::Vector2d u = b - a, v = c - a;
    area += 0.5 * (u.x() * v.y() - u.y() * v.x());
  }
  return area;
}

TEST(GarmentBuilder, PlacePanelPointUsesIntrinsicXyz) {
  Panel p;
  p.translation = {1, 2, 3};
  // Only about z: (1, 0) -> (0, 1).
  p.rotationDeg = {0, 0, 90};
  EXPECT_TRUE(placePanelPoint(p, {1, 0}, 1.0).isApprox(Eigen::Vector3d(1, 3, 3), 1e-12));
  // R = Rx(90) * Ry(90): Ry takes x to -z, Rx takes -z to +y. (Rz*Ry*Rx would
  // give -z instead.)
  p.rotationDeg = {90, 90, 0};
  p.translation = {0, 0, 0};
  EXPECT_TRUE(placePanelPoint(p, {1, 0}, 1.0).isApprox(Eigen::Vector3d(0, 1, 0), 1e-12));
  // Units: 100 file units per metre.
  p.rotationDeg = {0, 0, 0};
  p.translation = {100, 0, -50};
  EXPECT_TRUE(placePanelPoint(p, {20, 30}, 100.0).isApprox(Eigen::Vector3d(1.2, 0.3, -0.5), 1e-12));
}

TEST(GarmentBuilder, FrontBackGarment) {
  const Pattern pattern = frontBack();
  MeshingOptions options;
  options.targetEdgeLength = 0.02;
  const Garment g = buildGarment(pattern, options);

  ASSERT_EQ(g.panelNames, (std::vector<std::string>{"front", "back"}));
  EXPECT_EQ(g.rest.rows(), g.vertexCount());
  EXPECT_EQ(g.uvs, g.rest);
  EXPECT_EQ(g.vertexPanel.size(), g.vertexCount());
  EXPECT_EQ(g.trianglePanel.size(), g.triangleCount());
  // Panel areas in square metres: 0.5 * 0.6.
  EXPECT_NEAR(meshArea(g, 0), 0.30, 1e-12);
  EXPECT_NEAR(meshArea(g, 1), 0.30, 1e-12);
  // Triangles stay within one panel.
  for (int t = 0; t < g.triangleCount(); ++t) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(g.vertexPanel(g.triangles(t, k)), g.trianglePanel(t));
  }
  // 50 cm / 2 cm = 25 segments, 60 cm / 2 cm = 30 segments; edges run corner to
  // corner.
  ASSERT_EQ(g.edgeVertices.size(), 2u);
  for (int p = 0; p < 2; ++p) {
    ASSERT_EQ(g.edgeVertices[p].size(), 4u);
    EXPECT_EQ(g.edgeVertices[p][0].size(), 26u);
    EXPECT_EQ(g.edgeVertices[p][1].size(), 31u);
    EXPECT_EQ(g.edgeVertices[p][2].size(), 26u);
    EXPECT_EQ(g.edgeVertices[p][3].size(), 31u);
    for (int e = 0; e < 4; ++e) {
      EXPECT_EQ(g.edgeVertices[p][e].back(),
                g.edgeVertices[p][(e + 1) % 4].front());  // shared corners
      const Eigen::Vector2d start = pattern.panels[p].vertices[e] / 100.0;
      const Eigen::Vector2d end = pattern.panels[p].vertices[(e + 1) % 4] / 100.0;
      const auto& ev = g.edgeVertices[p][e];
      for (size_t k = 0; k < ev.size(); ++k) {
        const double f = static_cast<double>(k) / static_cast<double>(ev.size() - 1);
        EXPECT_LT((start + f * (end - start) - g.rest.row(ev[k]).transpose()).norm(), 1e-12)
            << "panel " << p << " edge " << e << " point " << k;
      }
    }
  }
  // Placed positions: the front is the rest shape at z = 0.1; the back is
  // mirrored in x about 0.25.
  for (int v = 0; v < g.vertexCount(); ++v) {
    const Eigen::Vector2d r = g.rest.row(v);
    const Eigen::Vector3d expected =
        g.vertexPanel(v) == 0 ? Eigen::Vector3d(r.x(), r.y(), 0.1) : Eigen::Vector3d(0.5 - r.x(), r.y(), -0.1);
    EXPECT_LT((g.positions.row(v).transpose() - expected).norm(), 1e-12) << "vertex " << v;
  }
  // Stitches: 31 pairs each, partners one above the other (same x, y), 0.2 m
  // apart in z.
  ASSERT_EQ(g.stitches.size(), 2u);
  ASSERT_EQ(g.stitchPairs.size(), 62u);
  for (const GarmentStitch& s : g.stitches) {
    EXPECT_EQ(s.pairCount, 31);
    for (int k = s.firstPair; k < s.firstPair + s.pairCount; ++k) {
      const auto [a, b] = g.stitchPairs[k];
      EXPECT_EQ(g.vertexPanel(a), 0);
      EXPECT_EQ(g.vertexPanel(b), 1);
      const Eigen::Vector3d d = g.positions.row(a) - g.positions.row(b);
      EXPECT_NEAR(d.head<2>().norm(), 0.0, 1e-12) << "stitch " << s.stitch << " pair " << k;
      EXPECT_NEAR(d.z(), 0.2, 1e-12);
    }
  }
}

TEST(GarmentBuilder, StitchedEdgesShareTheLongerSideCount) {
  Pattern pattern;
  pattern.source = "test.json";
  pattern.unitsInMeter = 100.0;
  pattern.panels = {rectangle("a", 30, 40), rectangle("b", 20, 25)};
  // a's edge 1 (40 cm) to b's edge 3 (25 cm): both sides get 40 / 2 = 20
  // segments.
  pattern.stitches.push_back(Stitch{{0, 1}, {1, 3}, false});
  // A chain: b's edge 1 (25 cm) to a's edge 3 (40 cm) also gives 20.
  pattern.stitches.push_back(Stitch{{1, 1}, {0, 3}, true});
  MeshingOptions options;
  options.targetEdgeLength = 0.02;
  const Garment g = buildGarment(pattern, options);
  EXPECT_EQ(g.edgeVertices[0][1].size(), 21u);
  EXPECT_EQ(g.edgeVertices[1][3].size(), 21u);
  EXPECT_EQ(g.edgeVertices[1][1].size(), 21u);
  EXPECT_EQ(g.edgeVertices[0][0].size(), 16u);  // unstitched 30 cm
  EXPECT_EQ(g.edgeVertices[1][0].size(), 11u);  // unstitched 20 cm
  // rightWrong false: a[k] with b[n - k]; true: a[k] with b[k].
  const GarmentStitch& s0 = g.stitches[0];
  const GarmentStitch& s1 = g.stitches[1];
  EXPECT_EQ(g.stitchPairs[s0.firstPair], std::make_pair(g.edgeVertices[0][1].front(), g.edgeVertices[1][3].back()));
  EXPECT_EQ(g.stitchPairs[s1.firstPair], std::make_pair(g.edgeVertices[1][1].front(), g.edgeVertices[0][3].front()));
  EXPECT_EQ(g.stitchPairs[s1.firstPair + 20], std::make_pair(g.edgeVertices[1][1].back(), g.edgeVertices[0][3].back()));
  EXPECT_NEAR(meshArea(g, 0), 0.12, 1e-12);
  EXPECT_NEAR(meshArea(g, 1), 0.05, 1e-12);
}

TEST(GarmentBuilder, GrainLineTurnsTheMaterialFrame) {
  // Front's grain runs up its y axis, back has none: front's rest coordinates are its uvs turned by -90 degrees,
  // so that the grain becomes the warp (+x); back's are its uvs.
  Pattern pattern = frontBack();
  pattern.panels[0].grainLine = std::array<Eigen::Vector2d, 2>{Eigen::Vector2d(25, 5), Eigen::Vector2d(25, 55)};
  MeshingOptions options;
  options.targetEdgeLength = 0.1;
  const Garment g = buildGarment(pattern, options);
  int checked = 0;
  for (int v = 0; v < g.vertexCount(); ++v) {
    const Eigen::Vector2d uv = g.uvs.row(v), rest = g.rest.row(v);
    const Eigen::Vector2d expected = g.vertexPanel(v) == 0 ? Eigen::Vector2d(uv.y(), -uv.x()) : uv;
    EXPECT_NEAR((rest - expected).norm(), 0.0, 1e-12) << "vertex " << v;
    checked += g.vertexPanel(v) == 0;
  }
  EXPECT_GT(checked, 10);
  // A turn keeps every triangle's area and orientation.
  EXPECT_NEAR(meshArea(g, 0), 0.5 * 0.6, 1e-9);
}

TEST(GarmentBuilder, RejectsBadInput) {
  MeshingOptions options;
  Pattern pattern = frontBack();
  options.targetEdgeLength = 0.0;
  EXPECT_THROW(buildGarment(pattern, options), InputError);
  options.targetEdgeLength = 0.02;
  pattern.stitches.push_back(Stitch{{0, 7}, {1, 0}, false});
  try {
    buildGarment(pattern, options);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "test.json: stitch 2 side a: edge 7 out "
              "of range (panel 'front' has 4 edges)");
  }
  // Too fine: a 50 x 60 cm panel at 0.1 mm is about 7e7 triangles.
  pattern = frontBack();
  options.targetEdgeLength = 1e-4;
  try {
    buildGarment(pattern, options);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("test.json: panel 'front': "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("limit"), std::string::npos) << e.what();
  }
}

TEST(GarmentBuilder, WarnsAboutEdgesInSeveralStitches) {
  Pattern pattern = frontBack();
  pattern.stitches.push_back(Stitch{{0, 1}, {1, 1}, true});
  Diagnostics diagnostics;
  MeshingOptions options;
  options.targetEdgeLength = 0.05;
  buildGarment(pattern, options, &diagnostics);
  ASSERT_EQ(diagnostics.warnings().size(), 2u);
  EXPECT_EQ(diagnostics.warnings()[0], "test.json: panel 'front' edge 1: used in 2 stitches");
}

}  // namespace
}  // namespace drape
