// Edge stitches in the Newton drape (non-conforming seams, pd-dd section 4.4): a vertex tied to the point
// (1 - t) x_a + t x_b of an edge. Energy value against a hand computation, gradient and Hessian against central
// finite differences, the static pattern, validation messages, a drape that closes a seam between panels
// meshed at different resolutions, and the t-shirt built with non-conforming seams (mesh.conforming_seams false).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <filesystem>
#include <random>

#include "drape/core/input_error.h"
#include "drape/garment/garment_builder.h"
#include "drape/newton/newton_solver.h"
#include "drape/newton/springs.h"
#include "drape/pattern/pattern_loader.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "newton_test_cloths.h"
#include "shared_data.h"

using namespace drape::newton;

namespace {

// Random flat positions of n vertices in a 0.2 m box, seeded.
Eigen::VectorXd randomPositions(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  Eigen::VectorXd x(3 * n);
  for (int i = 0; i < x.size(); ++i) x[i] = u(rng);
  return x;
}

Eigen::VectorXd gradientOf(const Energy& e, const Eigen::VectorXd& x) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  e.addGradient(x, g);
  return g;
}

// Hessian assembled on the energy's own static pattern, as a dense matrix; fails the test when a block fell
// outside the pattern (into the dynamic part).
Eigen::MatrixXd hessianOf(const Energy& e, const Eigen::VectorXd& x) {
  std::vector<std::pair<int, int>> pairs;
  e.addCouplings(pairs);
  BlockMatrix h;
  h.build(static_cast<int>(x.size() / 3), pairs);
  e.addHessian(x, h);
  EXPECT_EQ(h.dynamicBlockCount(), 0) << "Hessian blocks outside the static pattern";
  return Eigen::MatrixXd(h.toSparse());
}

}  // namespace

TEST(NewtonEdgeStitch, ValueMatchesHandComputation) {
  // v = (0, 0, 1), edge (0, 0, 0) -> (1, 0, 0), t = 0.25: edge point (0.25, 0, 0), c = (-0.25, 0, 1).
  Eigen::VectorXd x(9);
  x << 0, 0, 1, 0, 0, 0, 1, 0, 0;
  StitchSprings e({}, 200.0, {drape::model::EdgeStitch{0, 1, 2, 0.25}});
  EXPECT_NEAR(e.value(x), 0.5 * 200.0 * (0.0625 + 1.0), 1e-12);
  EXPECT_NEAR(e.maxGap(x), std::sqrt(1.0625), 1e-12);
  // Gradient: k w_i c with w = (1, -0.75, -0.25).
  const Eigen::VectorXd g = gradientOf(e, x);
  const Eigen::Vector3d c(-0.25, 0.0, 1.0);
  EXPECT_LT((g.segment<3>(0) - 200.0 * c).norm(), 1e-12);
  EXPECT_LT((g.segment<3>(3) + 0.75 * 200.0 * c).norm(), 1e-12);
  EXPECT_LT((g.segment<3>(6) + 0.25 * 200.0 * c).norm(), 1e-12);
  // The forces balance (translation invariance): sum of weights is 0.
  EXPECT_LT((g.segment<3>(0) + g.segment<3>(3) + g.segment<3>(6)).norm(), 1e-12);
  // t = 0 is the vertex stitch (v, a); t = 1 the vertex stitch (v, b).
  const Eigen::VectorXd y = randomPositions(3, 5);
  StitchSprings atA({}, 200.0, {drape::model::EdgeStitch{0, 1, 2, 0.0}}), pairA({{0, 1}}, 200.0);
  StitchSprings atB({}, 200.0, {drape::model::EdgeStitch{0, 1, 2, 1.0}}), pairB({{2, 0}}, 200.0);
  EXPECT_NEAR(atA.value(y), pairA.value(y), 1e-14);
  EXPECT_NEAR(atB.value(y), pairB.value(y), 1e-14);
  EXPECT_LT((gradientOf(atA, y) - gradientOf(pairA, y)).norm(), 1e-12);
  EXPECT_LT((hessianOf(atB, y) - hessianOf(pairB, y)).norm(), 1e-12);
  // A vertex stitched to itself (a dart tip on both sides of its seam) adds nothing, not even Hessian blocks.
  StitchSprings self({{1, 1}}, 200.0);
  EXPECT_EQ(self.value(y), 0.0);
  EXPECT_EQ(gradientOf(self, y).norm(), 0.0);
  EXPECT_EQ(hessianOf(self, y).norm(), 0.0);
  // A vertex on its edge point has zero energy.
  Eigen::VectorXd on = y;
  on.segment<3>(0) = 0.6 * y.segment<3>(3) + 0.4 * y.segment<3>(6);
  EXPECT_NEAR(StitchSprings({}, 200.0, {drape::model::EdgeStitch{0, 1, 2, 0.4}}).value(on), 0.0, 1e-15);
}

TEST(NewtonEdgeStitch, GradientAndHessianMatchFiniteDifferences) {
  const int n = 7;
  const std::vector<drape::model::EdgeStitch> edges = {{0, 1, 2, 0.3}, {3, 2, 4, 0.75}, {5, 6, 1, 0.0}, {6, 3, 5, 1.0}};
  StitchSprings e({{0, 4}, {5, 2}}, 1.7e3, edges);  // vertex and edge stitches mixed, sharing vertices
  for (unsigned seed : {1u, 2u, 3u}) {
    const Eigen::VectorXd x = randomPositions(n, seed);
    const Eigen::VectorXd g = gradientOf(e, x);
    const double step = 1e-6;
    Eigen::VectorXd gfd(3 * n);
    Eigen::MatrixXd hfd(3 * n, 3 * n);
    for (int k = 0; k < 3 * n; ++k) {
      Eigen::VectorXd xp = x, xm = x;
      xp[k] += step;
      xm[k] -= step;
      gfd[k] = (e.value(xp) - e.value(xm)) / (2 * step);
      hfd.col(k) = (gradientOf(e, xp) - gradientOf(e, xm)) / (2 * step);
    }
    ASSERT_GT(g.norm(), 0.0);
    EXPECT_LT((g - gfd).norm() / gfd.norm(), 1e-7) << "seed " << seed;
    const Eigen::MatrixXd h = hessianOf(e, x);
    EXPECT_LT((h - hfd).norm() / hfd.norm(), 1e-6) << "seed " << seed;
    EXPECT_LT((h - h.transpose()).norm(), 1e-12 * h.norm());
    // Sum of zero-length springs: positive semi-definite, with the translations in its null space.
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(h);
    EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-9 * eig.eigenvalues().maxCoeff());
    Eigen::VectorXd shift(3 * n);
    for (int v = 0; v < n; ++v) shift.segment<3>(3 * v) = Eigen::Vector3d(0.3, -1.0, 2.0);
    EXPECT_LT((h * shift).norm(), 1e-10 * h.norm());
  }
  // Couplings: every pair of a stencil (v, a), (v, b), (a, b), so the static pattern holds all blocks.
  std::vector<std::pair<int, int>> pairs;
  StitchSprings({}, 1.0, {drape::model::EdgeStitch{0, 1, 2, 0.5}}).addCouplings(pairs);
  ASSERT_EQ(pairs.size(), 3u);
  BlockMatrix pattern(3, pairs);
  EXPECT_EQ(pattern.staticBlockCount(), 9);
}

TEST(NewtonEdgeStitch, ValidationNamesTheBadStitch) {
  drape::model::ClothModel m;
  m.fabrics = {drape::model::TriangleFabric{}};
  appendGridPanel(m, 3, 3, 0.1, 0.1, Eigen::Vector3d::Zero());  // 9 vertices
  auto message = [&](drape::model::EdgeStitch e) -> std::string {
    drape::model::ClothModel bad = m;
    bad.edgeStitches = {drape::model::EdgeStitch{0, 4, 5, 0.5}, e};
    try {
      drape::model::validateStitches(bad);
    } catch (const drape::InputError& err) {
      return err.what();
    }
    return "no error";
  };
  EXPECT_EQ(message({9, 4, 5, 0.5}), "cloth model: edge stitch 1: vertex 9 out of range (9 vertices)");
  EXPECT_EQ(message({0, 4, -2, 0.5}), "cloth model: edge stitch 1: edge end b -2 out of range (9 vertices)");
  EXPECT_EQ(message({0, 4, 5, 1.25}), "cloth model: edge stitch 1: t = 1.25 outside [0, 1]");
  EXPECT_EQ(message({0, 4, 5, std::nan("")}), "cloth model: edge stitch 1: t = nan outside [0, 1]");
  EXPECT_EQ(message({5, 4, 5, 0.5}), "cloth model: edge stitch 1: vertex 5 is an end of its own edge (4, 5)");
  EXPECT_EQ(message({0, 4, 4, 0.5}), "cloth model: edge stitch 1: edge (4, 4) is degenerate");
  EXPECT_EQ(message({0, 4, 5, 1.0}), "no error");
  // The Newton solver refuses such a model with the same message.
  drape::model::ClothModel bad = m;
  bad.edgeStitches = {drape::model::EdgeStitch{2, 2, 5, 0.5}};
  EXPECT_THROW(NewtonSolver(bad, NewtonSettings{}), drape::InputError);
}

TEST(NewtonEdgeStitch, DrapeClosesANonConformingSeam) {
  // Two 0.2 m panels meshed at different spacings (6 x 6 and 9 x 11 vertices), 5 cm apart. Every vertex of the
  // fine panel's left column is stitched to the point at its height on the coarse panel's right column.
  const int n1 = 6, nx2 = 9, ny2 = 11;
  const double size = 0.2, gap = 0.05;
  drape::model::ClothModel m;
  drape::model::TriangleFabric cotton;
  cotton.stretchWarp = cotton.stretchWeft = 5000.0;
  cotton.shear = 250.0;
  m.fabrics = {cotton};
  appendGridPanel(m, n1, n1, size, size, Eigen::Vector3d::Zero());
  appendGridPanel(m, nx2, ny2, size, size, Eigen::Vector3d(size + gap, 0.0, 0.0));
  const int base = n1 * n1;
  const double h1 = size / (n1 - 1);
  for (int j = 0; j < ny2; ++j) {
    const double y = size * j / (ny2 - 1);
    const int e = std::min(static_cast<int>(y / h1), n1 - 2);
    m.edgeStitches.push_back(
        {base + j * nx2, e * n1 + n1 - 1, (e + 1) * n1 + n1 - 1, std::clamp(y / h1 - e, 0.0, 1.0)});
  }
  m.pinned = {n1 * (n1 - 1), base + nx2 * ny2 - 1};  // top outer corners, held a rest width apart
  m.pinTargets = {Eigen::Vector3d(0, size, 0), Eigen::Vector3d(2 * size, size, 0)};
  NewtonSolver solver(m, NewtonSettings{});
  const StitchSprings probe({}, 1.0, m.edgeStitches);
  EXPECT_NEAR(probe.maxGap(solver.positions()), gap, 1e-12);
  bool hasStitchEnergy = false;
  for (const std::string& name : solver.energyNames()) hasStitchEnergy |= name == "stitches";
  EXPECT_TRUE(hasStitchEnergy);
  while (solver.time() < 0.5) ASSERT_NE(solver.step().status, NewtonStatus::Diverged);
  const Eigen::VectorXd& x = solver.positions();
  ASSERT_TRUE(x.allFinite());
  // Independent gap measurement from the positions.
  double worst = 0.0;
  for (const drape::model::EdgeStitch& e : m.edgeStitches)
    worst = std::max(
        worst, (x.segment<3>(3 * e.vertex) - (1 - e.t) * x.segment<3>(3 * e.a) - e.t * x.segment<3>(3 * e.b)).norm());
  std::printf("non-conforming seam gap after 0.5 s: %.3e m\n", worst);
  EXPECT_NEAR(worst, probe.maxGap(x), 1e-15);
  EXPECT_LT(worst, 1e-3);
  // Closed by pulling the panels together: the bottom row keeps most of its 0.4 m width.
  EXPECT_GT(x[3 * (base + nx2 - 1)] - x[0], 0.3);
}

// The t-shirt asset built with every edge sampled at its own spacing (body panels at 4 cm, sleeves at 2.5 cm):
// seams whose sides got different point counts become edge stitches, and a short Newton drape (no avatar, no gravity)
// closes every seam.
TEST(NewtonEdgeStitch, TshirtNonConformingSeamsCloseInADrape) {
  const drape::Pattern pattern = drape::loadPattern(drape::test::assetsDir() / "patterns" / "tshirt.json");
  drape::MeshingOptions options;
  options.targetEdgeLength = 0.04;
  // Finer sleeves: the sleeve-to-body seams get different point counts on their two sides.
  for (const char* sleeve : {"l_sleeve_front", "l_sleeve_back", "r_sleeve_front", "r_sleeve_back"})
    options.panelTargetEdgeLength[sleeve] = 0.025;
  const drape::Garment conforming = drape::buildGarment(pattern, options);
  drape::MeshingOptions wrong = options;
  wrong.panelTargetEdgeLength["sleeve"] = 0.02;
  try {
    drape::buildGarment(pattern, wrong);
    ADD_FAILURE() << "no error for an unknown panel";
  } catch (const drape::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("target edge length given for panel 'sleeve', which the pattern lacks"),
              std::string::npos)
        << e.what();
  }
  options.conformingSeams = false;
  const drape::Garment g = drape::buildGarment(pattern, options);
  EXPECT_TRUE(conforming.edgeStitches.empty());
  ASSERT_FALSE(g.edgeStitches.empty());
  ASSERT_EQ(g.stitches.size(), pattern.stitches.size());
  // Every seam is sewn one way or the other; the edge stitches of a seam run along its fine side, whose ends map
  // to the coarse side's ends (t = 0 or 1 on its end segments).
  int nonConforming = 0;
  for (const drape::GarmentStitch& s : g.stitches) {
    EXPECT_GT(s.pairCount + s.edgeStitchCount, 0) << "stitch " << s.stitch;
    if (s.edgeStitchCount == 0) continue;
    ++nonConforming;
    EXPECT_EQ(s.pairCount, 0);
    const drape::GarmentEdgeStitch& first = g.edgeStitches[s.firstEdgeStitch];
    const drape::GarmentEdgeStitch& last = g.edgeStitches[s.firstEdgeStitch + s.edgeStitchCount - 1];
    EXPECT_TRUE(first.t == 0.0 || first.t == 1.0) << "stitch " << s.stitch << " t " << first.t;
    EXPECT_TRUE(last.t == 0.0 || last.t == 1.0) << "stitch " << s.stitch << " t " << last.t;
    // The edge lies on one side's panel, the stitched vertex on the other side's.
    const drape::Stitch& st = pattern.stitches[s.stitch];
    for (int k = s.firstEdgeStitch; k < s.firstEdgeStitch + s.edgeStitchCount; ++k) {
      const drape::GarmentEdgeStitch& e = g.edgeStitches[k];
      EXPECT_EQ(g.vertexPanel[e.a], g.vertexPanel[e.b]);
      const int pv = g.vertexPanel[e.vertex], pe = g.vertexPanel[e.a];
      EXPECT_TRUE((pv == st.a.panel && pe == st.b.panel) || (pv == st.b.panel && pe == st.a.panel)) << "stitch " << k;
    }
  }
  std::printf(
      "t-shirt at 4 / 2.5 cm: %d of %zu seams non-conforming, %zu edge stitches, %zu vertex pairs (conforming "
      "build: %zu pairs)\n",
      nonConforming, g.stitches.size(), g.edgeStitches.size(), g.stitchPairs.size(), conforming.stitchPairs.size());
  EXPECT_GT(nonConforming, 0);

  drape::model::ClothModel m;
  m.restCoords = g.rest;
  m.triangles = g.triangles;
  m.fabrics = {drape::model::TriangleFabric{}};
  m.positions.resize(3 * g.vertexCount());
  for (int v = 0; v < g.vertexCount(); ++v) m.positions.segment<3>(3 * v) = g.positions.row(v).transpose();
  m.stitches = g.stitchPairs;
  for (const drape::GarmentEdgeStitch& e : g.edgeStitches) m.edgeStitches.push_back({e.vertex, e.a, e.b, e.t});
  m.gravity.setZero();
  NewtonSolver solver(m, NewtonSettings{});
  const StitchSprings probe(m.stitches, 1.0, m.edgeStitches);
  const double before = probe.maxGap(solver.positions());
  while (solver.time() < 0.3) ASSERT_NE(solver.step().status, NewtonStatus::Diverged) << "t = " << solver.time();
  const Eigen::VectorXd& x = solver.positions();
  ASSERT_TRUE(x.allFinite());
  double pairGap = 0.0, edgeGap = 0.0;
  for (auto [i, j] : m.stitches) pairGap = std::max(pairGap, (x.segment<3>(3 * i) - x.segment<3>(3 * j)).norm());
  for (const drape::model::EdgeStitch& e : m.edgeStitches)
    edgeGap = std::max(
        edgeGap, (x.segment<3>(3 * e.vertex) - (1 - e.t) * x.segment<3>(3 * e.a) - e.t * x.segment<3>(3 * e.b)).norm());
  std::printf("t-shirt seams: largest gap %.3f m placed, after 0.3 s: pairs %.2e m, edge stitches %.2e m\n", before,
              pairGap, edgeGap);
  EXPECT_GT(before, 0.05);
  EXPECT_LT(pairGap, 1e-3);
  EXPECT_LT(edgeGap, 1e-3);
}

// The scene setting mesh.conforming_seams reaches the garment builder and the solvers' cloth model. The GarmentCode
// pencil dress has seams whose two sides differ in length, so a uniform target edge length already samples them
// differently (the t-shirt's seams match in length: it needs per-panel targets, above).
TEST(NewtonEdgeStitch, ConformingSeamsSettingReachesTheSimulation) {
  DRAPE_SHARED_FILE(dress, "garmentcode/dress_pencil_specification.json");
  auto simulate = [&](const char* conforming) {
    drape::SceneRequest request;
    request.input = dress;
    request.overrides = {
        {"mesh.target_edge_length", "0.04"}, {"mesh.conforming_seams", conforming}, {"solver.stage", "preview"}};
    return std::make_unique<drape::Simulation>(drape::loadScene(request));
  };
  EXPECT_TRUE(simulate("true")->garment().edgeStitches.empty());
  const auto sim = simulate("false");
  const drape::Garment& g = sim->garment();
  drape::MeshingOptions options;
  options.targetEdgeLength = 0.04;
  options.conformingSeams = false;
  const drape::Garment expected = drape::buildGarment(drape::loadPattern(dress), options);
  ASSERT_FALSE(g.edgeStitches.empty());
  EXPECT_EQ(g.edgeStitches.size(), expected.edgeStitches.size());
  EXPECT_EQ(g.stitchPairs.size(), expected.stitchPairs.size());
  auto maxGap = [&g](const Eigen::MatrixX3d& x) {
    double gap = 0.0;
    for (const drape::GarmentEdgeStitch& e : g.edgeStitches)
      gap = std::max(gap, (x.row(e.vertex) - (1 - e.t) * x.row(e.a) - e.t * x.row(e.b)).norm());
    return gap;
  };
  const double before = maxGap(sim->positions());
  for (int i = 0; i < 40; ++i) ASSERT_NE(sim->step().status, drape::StepStatus::Diverged) << "step " << i;
  const double after = maxGap(sim->positions());
  std::printf(
      "pencil dress, %zu edge stitches: largest edge-stitch gap %.3f m placed, %.2e m after 40 preview "
      "steps\n",
      g.edgeStitches.size(), before, after);
  EXPECT_LT(after, 0.5 * before);
}
