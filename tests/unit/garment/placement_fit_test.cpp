// The placement fit (garment/placement_fit.h, through buildSceneGarment): patterns laid out for the avatar they are
// on stay where they are; GarmentCode's shirt, laid out for mean_all, is moved onto a mannequin 15 % broader at the
// shoulders and 10 % taller (tests/data/bodies/broad_tall.yaml) with no vertex inside the body, its sleeves around
// the arms and a warning naming the panels it moved far. That it is less strained after a short drape than without the
// fit is a slow test (tests/slow/placement_fit_drape_test.cpp).
#include "drape/garment/placement_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "drape/avatar/body_landmarks.h"
#include "drape/collision/avatar_collider.h"
#include "drape/scene/scene.h"
#include "drape/sim/scene_garment.h"
#include "placement_fit_support.h"
#include "shared_data.h"

namespace drape {
namespace {

double maxMove(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  return (a - b).rowwise().norm().maxCoeff();
}

bool warnedAboutAMove(const Diagnostics& d) {
  for (const std::string& w : d.warnings())
    if (w.find("placement: panel '") != std::string::npos) return true;
  return false;
}

void expectStaysPut(const std::filesystem::path& file) {
  SCOPED_TRACE(file.string());
  SceneRequest request;
  request.input = file;
  Diagnostics on, off;
  const Garment fitted = buildSceneGarment(sceneWithFit(request, true), &on);
  const Garment asLaidOut = buildSceneGarment(sceneWithFit(request, false), &off);
  ASSERT_EQ(fitted.vertexCount(), asLaidOut.vertexCount());
  EXPECT_LT(maxMove(fitted.positions, asLaidOut.positions), 0.01);
  EXPECT_FALSE(warnedAboutAMove(on));
}

class LibraryScenes : public ::testing::TestWithParam<const char*> {};

TEST_P(LibraryScenes, FittedPatternStaysWhereItIs) {
  expectStaysPut(test::assetsDir() / "scenes" / (std::string(GetParam()) + ".json"));
}

INSTANTIATE_TEST_SUITE_P(PlacementFit, LibraryScenes,
                         ::testing::Values("tshirt", "default", "aline_skirt", "trousers", "sleeveless_dress",
                                           "shirt_over_skirt"));

TEST(PlacementFit, GarmentCodePatternsStayOnTheBodyTheyWereMadeFor) {
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  for (const char* scene : {"shirt_mean_on_mean_all.json", "dress_pencil_on_mean_all.json"})
    expectStaysPut(test::testDataDir() / "scenes" / scene);
}

// The library t-shirt moved 10 cm forward by placement.translate: its back panel cuts into the mannequin's back. Front
// to back the fit aligns nothing, so only the push out of the body moves it: the back panel, backwards, until no
// vertex is inside.
TEST(PlacementFit, PanelsInsideTheBodyArePushedOut) {
  SceneRequest request;
  request.input = test::assetsDir() / "scenes" / "tshirt.json";
  request.overrides.push_back({"placement.translate", "0,0,0.1"});
  const Scene on = sceneWithFit(request, true), off = sceneWithFit(request, false);
  const collision::AvatarCollider body(on.avatar);
  auto inside = [&](const Garment& g, const std::string& panel) {
    int n = 0;
    for (int v = 0; v < g.vertexCount(); ++v)
      if (g.panelNames[g.vertexPanel(v)] == panel) n += body.signedDistance(g.positions.row(v).transpose()) < 0;
    return n;
  };
  Diagnostics d;
  const Garment asLaidOut = buildSceneGarment(off, nullptr), fitted = buildSceneGarment(on, &d);
  ASSERT_GT(inside(asLaidOut, "back"), 0);
  EXPECT_EQ(inside(fitted, "back"), 0);
  // The back panel moved back; the front panel, clear of the body, stayed.
  for (int v = 0; v < fitted.vertexCount(); ++v) {
    const Eigen::Vector3d move = (fitted.positions.row(v) - asLaidOut.positions.row(v)).transpose();
    const std::string& panel = fitted.panelNames[fitted.vertexPanel(v)];
    if (panel == "back") {
      EXPECT_LT(move.z(), 0.0);
      EXPECT_LT(std::abs(move.x()), 0.1 * std::abs(move.z()));  // away from the body's axis: about straight back
      EXPECT_NEAR(move.y(), 0.0, 1e-9);                         // horizontally
    } else if (panel == "front") {
      EXPECT_EQ(move.norm(), 0.0);
    }
  }
}

// An avatar that is no standing body (a cube) gets no fit, and one warning says so.
TEST(PlacementFit, AvatarWithoutLandmarksLeavesThePatternAsLaidOut) {
  SceneRequest request;
  request.input = test::assetsDir() / "patterns" / "tshirt.json";
  request.avatarFile = (test::testDataDir() / "avatars" / "cube.obj").string();
  const Scene on = sceneWithFit(request, true), off = sceneWithFit(request, false);
  Diagnostics d;
  const Garment fitted = buildSceneGarment(on, &d), asLaidOut = buildSceneGarment(off, nullptr);
  EXPECT_EQ(maxMove(fitted.positions, asLaidOut.positions), 0.0);
  int warned = 0;
  for (const std::string& w : d.warnings())
    warned += w.find("placement: the pattern is placed as laid out") != std::string::npos;
  EXPECT_EQ(warned, 1);
}

// Distance from p to the line of axis.
double distanceToAxis(const Eigen::Vector3d& p, const BodyAxis& axis) {
  const Eigen::Vector3d q = p - axis.origin;
  return (q - axis.direction * q.dot(axis.direction)).norm();
}

// Garment vertices inside the body, and sleeve vertices nearer the body's vertical axis than their own arm's axis.
struct Start {
  int inside = 0;
  int sleeveVertices = 0;
  int sleeveOffTheArm = 0;
};

Start startOf(const Garment& garment, const TriangleMesh& body) {
  const collision::AvatarCollider collider(body);
  const BodyLandmarks landmarks = findBodyLandmarks(body);
  Start s;
  for (int v = 0; v < garment.vertexCount(); ++v) {
    const Eigen::Vector3d p = garment.positions.row(v).transpose();
    s.inside += collider.signedDistance(p) < 0;
    const std::string& panel = garment.panelNames[garment.vertexPanel(v)];
    if (panel.find("sleeve") == std::string::npos) continue;
    const BodyAxis& arm = panel.rfind("left", 0) == 0 ? landmarks.leftArm : landmarks.rightArm;
    const Eigen::Vector3d c = landmarks.centreAt(p.y());
    ++s.sleeveVertices;
    s.sleeveOffTheArm += distanceToAxis(p, arm) >= Eigen::Vector2d(p.x() - c.x(), p.z() - c.z()).norm();
  }
  return s;
}

TEST_F(BroadTallBody, FittedShirtStartsOutsideTheBodyWithItsSleevesAroundTheArms) {
  DRAPE_SHARED_FILE(pattern, "garmentcode/shirt_mean_specification.json");
  Diagnostics diagnostics;
  const Start start = startOf(buildSceneGarment(shirt(pattern, true, 0.02), &diagnostics), *s_body);
  EXPECT_EQ(start.inside, 0);
  EXPECT_GT(start.sleeveVertices, 0);
  EXPECT_EQ(start.sleeveOffTheArm, 0);

  // The sleeves moved far, and the warning names the pattern file and the panel.
  bool named = false;
  for (const std::string& w : diagnostics.warnings())
    named = named ||
            (w.find("shirt_mean_specification.json: placement: panel 'left_sleeve_f' moved") != std::string::npos &&
             w.find("the pattern was laid out for another body") != std::string::npos);
  EXPECT_TRUE(named) << ::testing::PrintToString(diagnostics.warnings());
}

TEST_F(BroadTallBody, WithoutTheFitTheShirtStartsInsideTheBodyOrOffTheArms) {
  DRAPE_SHARED_FILE(pattern, "garmentcode/shirt_mean_specification.json");
  Diagnostics diagnostics;
  const Start start = startOf(buildSceneGarment(shirt(pattern, false, 0.02), &diagnostics), *s_body);
  EXPECT_GT(start.inside + start.sleeveOffTheArm, 0);
  EXPECT_FALSE(warnedAboutAMove(diagnostics));
}

}  // namespace
}  // namespace drape
