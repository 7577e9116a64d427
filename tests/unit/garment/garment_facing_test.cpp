// Garment faces point away from the body: garmentFacing against a sphere, and the placed GarmentCode and library
// garments on the bodies they were made for. GarmentCode marks a panel's outside by its outline's winding (its
// back panels run clockwise); buildGarment turns such panels' triangles over with it.
#include "drape/collision/garment_facing.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "drape/avatar/avatar_loader.h"
#include "drape/garment/garment_builder.h"
#include "drape/geometry/primitives.h"
#include "drape/pattern/pattern_loader.h"
#include "shared_data.h"

namespace drape {
namespace {

// A sphere of radius 0.52 m as a "garment" around a 0.5 m body sphere: its faces are outward (icosphere winding).
TEST(GarmentFacing, CountsFacesNearTheBodyByTheirWinding) {
  const collision::AvatarCollider body(makeIcosphere(Eigen::Vector3d::Zero(), 0.5, 3));
  TriangleMesh shell = makeIcosphere(Eigen::Vector3d::Zero(), 0.52, 2);
  collision::GarmentFacing f = collision::garmentFacing(shell.vertices, shell.triangles, body, 0.05);
  EXPECT_EQ(f.nearFaces, shell.triangleCount());
  EXPECT_EQ(f.outwardFaces, shell.triangleCount());
  // Half of the shell turned over (the faces with z > 0): half of them inward.
  int turned = 0;
  for (int t = 0; t < shell.triangleCount(); ++t) {
    const double z = (shell.vertices.row(shell.triangles(t, 0)) + shell.vertices.row(shell.triangles(t, 1)) +
                      shell.vertices.row(shell.triangles(t, 2)))(2);
    if (z > 0.0) {
      shell.triangles.row(t) = Eigen::RowVector3i(shell.triangles(t, 0), shell.triangles(t, 2), shell.triangles(t, 1));
      ++turned;
    }
  }
  f = collision::garmentFacing(shell.vertices, shell.triangles, body, 0.05);
  EXPECT_EQ(f.outwardFaces, shell.triangleCount() - turned);
  // Faces farther than nearDistance do not count.
  f = collision::garmentFacing(shell.vertices, shell.triangles, body, 0.01);
  EXPECT_EQ(f.nearFaces, 0);
  EXPECT_DOUBLE_EQ(f.outwardFraction(), 1.0);
}

// A clockwise outline turns its panel's triangles over: its placed normals are R * (-z).
TEST(GarmentFacing, ClockwiseOutlineTurnsThePanelOver) {
  Pattern pattern;
  pattern.source = "test.json";
  for (int k = 0; k < 2; ++k) {
    Panel p;
    p.name = k == 0 ? "ccw" : "cw";
    p.vertices = {{0, 0}, {40, 0}, {40, 30}, {0, 30}};
    const std::vector<int> order = k == 0 ? std::vector<int>{0, 1, 2, 3} : std::vector<int>{0, 3, 2, 1};
    for (int e = 0; e < 4; ++e) p.edges.push_back(PanelEdge{order[e], order[(e + 1) % 4], {}, ""});
    p.rotationDeg = {0, 30, 0};
    pattern.panels.push_back(p);
  }
  MeshingOptions options;
  options.targetEdgeLength = 0.05;
  const Garment g = buildGarment(pattern, options);
  const Eigen::Vector3d z = Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()) * Eigen::Vector3d::UnitZ();
  for (int t = 0; t < g.triangleCount(); ++t) {
    const Eigen::Vector3d a = g.positions.row(g.triangles(t, 0)), b = g.positions.row(g.triangles(t, 1)),
                          c = g.positions.row(g.triangles(t, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    EXPECT_NEAR(n.dot(z), g.trianglePanel(t) == 0 ? 1.0 : -1.0, 1e-9) << "triangle " << t;
  }
}

// Every face of the placed garment near the body (within 25 cm: the patterns are placed around the body with gaps
// of up to 20 cm) faces away from it.
void expectPlacedOutward(const Pattern& pattern, const TriangleMesh& bodyMesh, const Eigen::Vector3d& offset) {
  MeshingOptions options;
  options.targetEdgeLength = 0.02;
  options.placementOffset = offset;
  const Garment g = buildGarment(pattern, options);
  const collision::AvatarCollider body(bodyMesh);
  const collision::GarmentFacing f = collision::garmentFacing(g.positions, g.triangles, body, 0.25);
  EXPECT_GT(f.nearFaces, g.triangleCount() / 2);
  EXPECT_GE(f.outwardFraction(), 0.98) << f.outwardFaces << " of " << f.nearFaces;
}

TEST(GarmentFacing, GarmentCodePatternsArePlacedRightSideOut) {
  DRAPE_SHARED_FILE(body, "garmentcode/mean_all.obj");
  for (const char* name :
       {"garmentcode/shirt_mean_specification.json", "garmentcode/dress_pencil_specification.json"}) {
    SCOPED_TRACE(name);
    DRAPE_SHARED_FILE(file, name);
    expectPlacedOutward(loadPattern(file), loadAvatar(body), Eigen::Vector3d::Zero());
  }
}

TEST(GarmentFacing, LibraryGarmentsArePlacedRightSideOut) {
  const TriangleMesh body = loadAvatar(test::assetsDir() / "avatars" / "female.obj");
  for (const char* name : {"tshirt", "aline_skirt", "trousers", "sleeveless_dress"}) {
    SCOPED_TRACE(name);
    expectPlacedOutward(loadPattern(test::assetsDir() / "patterns" / (std::string(name) + ".json")), body,
                        Eigen::Vector3d::Zero());
  }
}

}  // namespace
}  // namespace drape
