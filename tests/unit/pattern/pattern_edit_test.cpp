// The pattern view's edits: each checked against the geometry of the pattern before the edit (a split curve must
// trace the same points as the whole one, a deleted vertex must undo an insertion), and every refusal names the
// panel and the element.
#include "drape/pattern/pattern_edit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "drape/core/input_error.h"
#include "drape/pattern/edge_curve.h"

namespace drape {
namespace {

// A 40 x 30 (cm) panel "front" with edges 0..3 counter-clockwise, and a 40 x 30 "back" sewn to it along edge 1;
// front's edge 2 (top) is the curve given.
Pattern twoPanels(const EdgeCurve& top) {
  Pattern pattern;
  pattern.source = "edit.json";
  for (const char* name : {"front", "back"}) {
    Panel p;
    p.name = name;
    p.vertices = {{0, 0}, {40, 0}, {40, 30}, {0, 30}};
    for (int e = 0; e < 4; ++e) p.edges.push_back(PanelEdge{e, (e + 1) % 4, {}, ""});
    pattern.panels.push_back(p);
  }
  pattern.panels[0].edges[2].curve = top;
  pattern.stitches.push_back(Stitch{{0, 1}, {1, 3}, false});
  pattern.stitches.push_back(Stitch{{0, 3}, {1, 1}, false});
  return pattern;
}

EdgeCurve quadratic() {
  EdgeCurve c;
  c.type = CurveType::Quadratic;
  c.controls = {{0.3, 0.25}};
  return c;
}

EdgeCurve cubic() {
  EdgeCurve c;
  c.type = CurveType::Cubic;
  c.controls = {{0.2, -0.3}, {0.7, 0.4}};
  return c;
}

EdgeCurve arc(bool large) {
  EdgeCurve c;
  c.type = CurveType::Circle;
  c.radius = 25.0;
  c.largeArc = large;
  c.right = true;
  return c;
}

std::string refusal(const std::function<void()>& edit) {
  try {
    edit();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

class SplitCurve : public ::testing::TestWithParam<EdgeCurve> {};

TEST_P(SplitCurve, HalvesTraceTheWholeEdge) {
  const Pattern before = twoPanels(GetParam());
  constexpr double t = 0.35;
  const Pattern after = insertVertex(before, 0, 2, t);
  const Panel& p = after.panels[0];
  ASSERT_EQ(p.vertices.size(), 5u);
  ASSERT_EQ(p.edges.size(), 5u);
  EXPECT_EQ(p.edges[2].end, 4);
  EXPECT_EQ(p.edges[3].start, 4);
  EXPECT_EQ(p.edges[3].end, 3);
  EXPECT_NEAR((p.vertices[4] - evaluateEdge(before.panels[0], 2, t)).norm(), 0.0, 1e-9);
  // The first half at u is the whole edge at t u, the second half at u is the whole edge at t + (1 - t) u.
  for (double u : {0.1, 0.5, 0.9}) {
    EXPECT_NEAR((evaluateEdge(p, 2, u) - evaluateEdge(before.panels[0], 2, t * u)).norm(), 0.0, 1e-9) << u;
    EXPECT_NEAR((evaluateEdge(p, 3, u) - evaluateEdge(before.panels[0], 2, t + (1 - t) * u)).norm(), 0.0, 1e-9) << u;
  }
  EXPECT_NEAR(edgeLength(p, 2) + edgeLength(p, 3), edgeLength(before.panels[0], 2), 1e-6);
  // The seam on the left side (front edge 3) follows its edge to index 4.
  EXPECT_EQ(after.stitches[1].a.edge, 4);
  EXPECT_EQ(after.stitches[0].a.edge, 1);
}

INSTANTIATE_TEST_SUITE_P(PatternEdit, SplitCurve,
                         ::testing::Values(EdgeCurve{}, quadratic(), cubic(), arc(false), arc(true)));

TEST(PatternEdit, DeletingTheInsertedVertexGivesThePatternBack) {
  const Pattern before = twoPanels(EdgeCurve{});
  const Pattern after = deleteVertex(insertVertex(before, 0, 2, 0.5), 0, 4);
  const Panel &a = before.panels[0], &b = after.panels[0];
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]);
  for (size_t e = 0; e < a.edges.size(); ++e) {
    EXPECT_EQ(a.edges[e].start, b.edges[e].start);
    EXPECT_EQ(a.edges[e].end, b.edges[e].end);
  }
  for (size_t s = 0; s < before.stitches.size(); ++s) {
    EXPECT_EQ(before.stitches[s].a.edge, after.stitches[s].a.edge);
    EXPECT_EQ(before.stitches[s].b.edge, after.stitches[s].b.edge);
  }
}

TEST(PatternEdit, DeletingACornerRenumbersVerticesEdgesAndSeams) {
  // A 5th vertex in front's bottom edge: front's sewn edges 1 and 3 become 2 and 4.
  const Pattern before = insertVertex(twoPanels(EdgeCurve{}), 0, 0, 0.5);
  EXPECT_EQ(before.stitches[0].a.edge, 2);
  EXPECT_EQ(before.stitches[1].a.edge, 4);
  // Front's corner 2 ends its sewn right edge; back's corner 1 starts its sewn edge 1.
  EXPECT_NE(refusal([&] { deleteVertex(before, 0, 2); }).find("unpick the seam"), std::string::npos);
  EXPECT_NE(refusal([&] { deleteVertex(before, 1, 1); }).find("panel 'back' edge 1 is sewn"), std::string::npos);
  // Back's corner 0 lies between its edge 3, sewn by seam 0, and edge 0: unpicked first, it goes.
  const Pattern unpicked = unpickSeam(before, 0);
  const Pattern after = deleteVertex(unpicked, 1, 0);
  const Panel& back = after.panels[1];
  ASSERT_EQ(back.vertices.size(), 3u);
  ASSERT_EQ(back.edges.size(), 3u);
  // The old corners 1, 2, 3 are now 0, 1, 2, and the loop closes.
  for (size_t e = 0; e < 3; ++e) EXPECT_EQ(back.edges[e].end, back.edges[(e + 1) % 3].start);
  EXPECT_EQ(back.vertices[0], Eigen::Vector2d(40, 0));
  // The remaining seam joined front edge 4 to back edge 1, which is now edge 0.
  ASSERT_EQ(after.stitches.size(), 1u);
  EXPECT_EQ(after.stitches[0].b.panel, 1);
  EXPECT_EQ(after.stitches[0].b.edge, 0);
  EXPECT_NE(refusal([&] { deleteVertex(after, 1, 0); }).find("at least three vertices"), std::string::npos);
}

TEST(PatternEdit, MovingAVertexCarriesItsCurve) {
  const Pattern before = twoPanels(quadratic());
  const Pattern after = moveVertex(before, 0, 3, {-5, 35});
  EXPECT_EQ(after.panels[0].vertices[3], Eigen::Vector2d(-5, 35));
  // The relative control point is kept, so the curve's end follows and its middle moves with the chord.
  EXPECT_NEAR((evaluateEdge(after.panels[0], 2, 1.0) - Eigen::Vector2d(-5, 35)).norm(), 0.0, 1e-12);
  EXPECT_EQ(after.panels[0].edges[2].curve.controls, before.panels[0].edges[2].curve.controls);
  EXPECT_NE(refusal([&] { moveVertex(before, 0, 9, {0, 0}); }).find("no vertex 9"), std::string::npos);
}

TEST(PatternEdit, MovingAControlPointPutsTheCurveThroughTheNewShape) {
  const Pattern before = twoPanels(quadratic());
  const Eigen::Vector2d to(20, 45);  // absolute
  const Pattern after = moveControlPoint(before, 0, 2, 0, to);
  // A quadratic Bezier's middle is (start + 2 control + end) / 4.
  const Eigen::Vector2d start(40, 30), end(0, 30);
  EXPECT_NEAR((evaluateEdge(after.panels[0], 2, 0.5) - (start + 2 * to + end) / 4).norm(), 0.0, 1e-9);
  EXPECT_NE(refusal([&] { moveControlPoint(before, 0, 0, 0, to); }).find("has no control points"), std::string::npos);
}

TEST(PatternEdit, SewingAndUnpicking) {
  Pattern p = twoPanels(EdgeCurve{});
  EXPECT_EQ(seamOfEdge(p, 0, 1), 0);
  EXPECT_EQ(seamOfEdge(p, 0, 0), -1);
  const Pattern sewn = sewEdges(p, {0, 0}, {1, 0});
  ASSERT_EQ(sewn.stitches.size(), 3u);
  EXPECT_EQ(seamOfEdge(sewn, 1, 0), 2);
  EXPECT_FALSE(sewn.stitches[2].rightWrong);
  EXPECT_NE(refusal([&] {
              sewEdges(sewn, {0, 0}, {1, 2});
            }).find("'front' edge 0 is sewn (seam 2)"),
            std::string::npos);
  EXPECT_NE(refusal([&] { sewEdges(p, {0, 2}, {0, 2}); }).find("cannot be sewn to itself"), std::string::npos);
  EXPECT_NE(refusal([&] { insertVertex(p, 0, 1, 0.5); }).find("unpick the seam before splitting"), std::string::npos);
  const Pattern unpicked = unpickSeam(sewn, 0);
  ASSERT_EQ(unpicked.stitches.size(), 2u);
  EXPECT_EQ(seamOfEdge(unpicked, 0, 1), -1);
  EXPECT_NE(refusal([&] { unpickSeam(p, 5); }).find("no seam 5"), std::string::npos);
}

TEST(PatternEdit, ValidationSpeaksAsTheLoader) {
  const Pattern p = twoPanels(EdgeCurve{});
  // Corner 2 dragged across the bottom edge: the outline crosses itself.
  const Pattern crossed = moveVertex(p, 0, 2, {20, -10});
  const std::string message = refusal([&] { validatedPattern(crossed); });
  EXPECT_NE(message.find("edit.json"), std::string::npos) << message;
  EXPECT_NE(message.find("panel 'front'"), std::string::npos) << message;
  // Front's top split near its end and the short piece sewn to back's 40 cm bottom: no seam, refused.
  const Pattern split = insertVertex(p, 0, 2, 0.8);
  const std::string seam = refusal([&] { validatedPattern(sewEdges(split, {0, 3}, {1, 0})); });
  EXPECT_NE(seam.find("more than twice the other"), std::string::npos) << seam;
  // A valid edit passes and comes back equal.
  const Pattern moved = validatedPattern(moveVertex(p, 0, 2, {42, 31}));
  EXPECT_EQ(moved.panels[0].vertices[2], Eigen::Vector2d(42, 31));
  EXPECT_EQ(moved.stitches.size(), p.stitches.size());
}

}  // namespace
}  // namespace drape
