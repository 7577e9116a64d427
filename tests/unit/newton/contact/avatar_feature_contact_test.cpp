// The avatar's sharp features against garment triangles (avatar_feature_contact.h): which avatar vertices are
// features (on a sphere, whose radius the chord estimate recovers within its normals' error; a cone's tip), the
// energy's derivatives against central differences, and a coarse cloth dropped on a small cone, which passes
// between the garment's vertices with vertex contact alone and holds the cloth with the feature contact. The default
// scene's drape, through which the mannequin's bust points no longer show, is a slow test
// (tests/slow/avatar_feature_contact_drape_test.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "drape/newton/contact/avatar_feature_contact.h"
#include "drape/newton/contact/contact_factory.h"
#include "drape/newton/contact/friction.h"
#include "drape/geometry/primitives.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "energy_fd_check.h"
#include "shared_data.h"

namespace drape::collision {
namespace {

using namespace drape::newton;  // the drape's contact energies

// Upright cone: tip at `tip`, base ring of `segments` vertices `height` below it, closed by a base centre vertex.
TriangleMesh makeCone(const Eigen::Vector3d& tip, double radius, double height, int segments) {
  TriangleMesh m;
  m.vertices.resize(segments + 2, 3);
  m.vertices.row(0) = tip.transpose();
  for (int k = 0; k < segments; ++k) {
    const double a = 2.0 * 3.14159265358979 * k / segments;
    m.vertices.row(1 + k) << tip.x() + radius * std::cos(a), tip.y() - height, tip.z() + radius * std::sin(a);
  }
  m.vertices.row(segments + 1) << tip.x(), tip.y() - height, tip.z();
  m.triangles.resize(2 * segments, 3);
  for (int k = 0; k < segments; ++k) {
    const int a = 1 + k, b = 1 + (k + 1) % segments;
    m.triangles.row(k) << 0, b, a;                     // side, counter-clockwise seen from outside
    m.triangles.row(segments + k) << segments + 1, a, b;  // base, seen from below
  }
  return m;
}

TEST(AvatarFeatureContact, FeaturesAreTheVerticesSharperThanTheRadius) {
  // Every vertex of an icosphere lies on the sphere, so the chord estimate |q - p|^2 / (2 n.(p - q)) would be the
  // radius itself with the radial normal; the area-weighted normal leans off it at the irregular vertices, which
  // puts the estimates between 0.84 and 1.03 times the radius (0.3 m).
  const TriangleMesh sphere = makeIcosphere(Eigen::Vector3d(0.1, 0.2, 0.3), 0.3, 3);
  EXPECT_EQ(avatarFeatureVertices(sphere, 0.25).size(), 0u);
  EXPECT_EQ(static_cast<int>(avatarFeatureVertices(sphere, 0.31).size()), sphere.vertexCount());
  // A cone's tip: its radius against the base ring is (r^2 + h^2) / (2 h).
  const double r = 0.08, h = 0.06, rc = (r * r + h * h) / (2.0 * h);
  const TriangleMesh cone = makeCone(Eigen::Vector3d(0.0, 1.0, 0.0), r, h, 24);
  auto tipIsFeature = [&](double maxRadius) {
    for (const FeatureVertex& f : avatarFeatureVertices(cone, maxRadius))
      if ((f.position - Eigen::Vector3d(0.0, 1.0, 0.0)).norm() < 1e-12) {
        EXPECT_GT(f.normal.y(), 1.0 - 1e-9);
        return true;
      }
    return false;
  };
  EXPECT_TRUE(tipIsFeature(rc * 1.01));
  EXPECT_FALSE(tipIsFeature(rc * 0.99));
  // The base centre is flat (its neighbours lie in its tangent plane): never a feature.
  for (const FeatureVertex& f : avatarFeatureVertices(cone, 1e3))
    EXPECT_GT((f.position - Eigen::Vector3d(0.0, 1.0 - h, 0.0)).norm(), 1e-9);
}

TEST(AvatarFeatureContact, DerivativesMatchFiniteDifferences) {
  // Two triangles over two features: one pair in the soft band (0 < s < thickness), one inside (s < 0).
  const std::vector<FeatureVertex> features = {{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 1.0, 0.0)},
                                               {Eigen::Vector3d(0.3, 0.0, 0.0), Eigen::Vector3d(0.6, 0.8, 0.0)}};
  Eigen::MatrixX3i triangles(2, 3);
  triangles << 0, 1, 2, 3, 4, 5;
  Eigen::VectorXd x(18);
  x << -0.03, 0.003, -0.02, 0.04, 0.002, -0.01, -0.01, 0.0025, 0.04,  // 3 mm above the first tip
      0.27, -0.002, -0.02, 0.34, -0.001, -0.01, 0.29, -0.0015, 0.04;   // 1.5 mm below the second
  ContactParameters params;
  params.stiffness = 100.0;
  params.thickness = 0.004;
  AvatarFeatureContactEnergy energy(features, triangles, params, 0.01);
  newton::StepContext ctx;
  ctx.previousPositions = &x;
  energy.beginStep(ctx);
  ASSERT_EQ(energy.pairCount(), 2);
  newton::checkEnergy(energy, x, true, 1e-7);
  // Nothing within reach: no pair, no energy.
  Eigen::VectorXd far = x;
  for (int v = 0; v < 6; ++v) far[3 * v + 1] += 0.5;
  ctx.previousPositions = &far;
  energy.beginStep(ctx);
  EXPECT_EQ(energy.pairCount(), 0);
  EXPECT_EQ(energy.value(far), 0.0);
}

TEST(AvatarFeatureContact, FactoryBuildsItAndFrictionHoldsItsPairs) {
  // A cone tip 1 mm under the middle of a triangle: the factory makes the feature term next to the avatar contact,
  // and friction lags the pair as a three-vertex stencil at the triangle's point.
  ContactSetup setup;
  setup.avatar = std::make_shared<AvatarCollider>(makeCone(Eigen::Vector3d::Zero(), 0.02, 0.02, 16));
  setup.avatarContact.thickness = 0.004;
  setup.featureRadius = 0.03;
  setup.featureReach = 0.02;
  setup.frictionCoefficient = 0.4;
  Eigen::MatrixX3i triangles(1, 3);
  triangles << 0, 1, 2;
  Eigen::VectorXd x(9);
  x << -0.05, 0.001, -0.03, 0.05, 0.001, -0.03, 0.0, 0.001, 0.06;
  auto energies = makeContactEnergies(setup, 3, triangles, {});
  ASSERT_EQ(energies.size(), 3u);
  EXPECT_EQ(energies[0]->name(), "avatar_contact");
  EXPECT_EQ(energies[1]->name(), "avatar_feature_contact");
  EXPECT_EQ(energies[2]->name(), "friction");
  newton::StepContext ctx;
  ctx.previousPositions = &x;
  for (auto& e : energies) e->beginStep(ctx);
  const auto& lagged = static_cast<const FrictionEnergy&>(*energies[2]).laggedContacts();
  ASSERT_EQ(lagged.size(), 1u);  // the vertices are 1 mm above the cone's base plane, far from its surface
  EXPECT_EQ(lagged[0].stencil.count, 3);
  EXPECT_NEAR(lagged[0].stencil.distance, 0.001, 1e-12);
  EXPECT_NEAR(lagged[0].normalForce, setup.avatarContact.stiffness * 0.003, 1e-9);
  setup.featureRadius = 0.0;
  EXPECT_EQ(makeContactEnergies(setup, 3, triangles, {}).size(), 2u);
}

// Height of the garment above (x, z): the highest triangle whose horizontal projection holds the point.
double clothHeightAbove(const Simulation& sim, double px, double pz) {
  const Eigen::MatrixX3d x = sim.positions();
  const Eigen::MatrixX3i& f = sim.garment().triangles;
  double best = -1e9;
  for (int t = 0; t < f.rows(); ++t) {
    const Eigen::Vector3d a = x.row(f(t, 0)), b = x.row(f(t, 1)), c = x.row(f(t, 2));
    const double det = (b.x() - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (b.z() - a.z());
    if (std::abs(det) < 1e-14) continue;
    const double u = ((px - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (pz - a.z())) / det;
    const double v = ((b.x() - a.x()) * (pz - a.z()) - (px - a.x()) * (b.z() - a.z())) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0) continue;
    best = std::max(best, a.y() + u * (b.y() - a.y()) + v * (c.y() - a.y()));
  }
  return best;
}

void writeObj(const TriangleMesh& m, const std::filesystem::path& path) {
  std::ofstream out(path);
  for (int v = 0; v < m.vertexCount(); ++v)
    out << "v " << m.vertices(v, 0) << " " << m.vertices(v, 1) << " " << m.vertices(v, 2) << "\n";
  for (int t = 0; t < m.triangleCount(); ++t)
    out << "f " << m.triangles(t, 0) + 1 << " " << m.triangles(t, 1) + 1 << " " << m.triangles(t, 2) + 1 << "\n";
}

TEST(AvatarFeatureContact, ConeTipStaysUnderACoarseCloth) {
  // A 1 m tablecloth meshed at 8 cm falls 6 cm onto the tip of a small cone (2.5 cm high and wide: a radius of
  // curvature of 2.5 cm by the chord estimate, under the 3 cm cap). The tip is placed off the mesh's vertices.
  const std::filesystem::path dir = test::testOutputDir() / "feature_contact";
  std::filesystem::create_directories(dir);
  const Eigen::Vector3d tip(0.031, 0.94, -0.017);
  writeObj(makeCone(tip, 0.025, 0.025, 32), dir / "cone.obj");
  std::ofstream(dir / "cone_scene.json")
      << R"({"pattern": ")" << (test::assetsDir() / "patterns" / "tablecloth.json").generic_string()
      << R"(", "avatar": {"file": ")" << (dir / "cone.obj").generic_string()
      << R"(", "units": "m"}, "fabric": {"preset": "cotton_shirting"}})";
  int featureContacts[2] = {-1, -1};  // in the last step's report, without and with the feature contact
  auto tipAboveCloth = [&](bool features) {
    SceneRequest request;
    request.input = dir / "cone_scene.json";
    request.overrides = {{"mesh.target_edge_length", "0.08"},  {"solver.stage", "drape"},
                         {"solver.max_sim_time", "0.35"},      {"contact.friction", "false"},
                         {"contact.avatar_features", features ? "true" : "false"}};
    Simulation sim(loadScene(request));
    const auto terms = sim.terms();
    EXPECT_EQ(std::find(terms.begin(), terms.end(), "avatar_feature_contact") != terms.end(), features);
    while (!sim.finished()) {
      const StepReport r = sim.step();
      featureContacts[features] = r.featureContacts;
      EXPECT_NE(r.status, StepStatus::Diverged) << "t = " << sim.time();
      if (r.status == StepStatus::Diverged) break;
    }
    return tip.y() - clothHeightAbove(sim, tip.x(), tip.z());
  };
  const double without = tipAboveCloth(false), with = tipAboveCloth(true);
  // Vertex contact alone: the tip passes between the vertices and the cloth falls on past it.
  EXPECT_GT(without, 1e-3) << "tip above the cloth by " << without << " m";
  // With the feature contact the cloth passes over the tip (the inside penalty lets it in by well under 1 mm).
  EXPECT_LT(with, 5e-4) << "tip above the cloth by " << with << " m";
  // The report counts the tip as a feature contact, and only when the term is on.
  EXPECT_EQ(featureContacts[0], 0);
  EXPECT_GE(featureContacts[1], 1);
}

}  // namespace
}  // namespace drape::collision
