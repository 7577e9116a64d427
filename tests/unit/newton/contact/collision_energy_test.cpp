// Contact energies: gradients and Hessians against central finite differences (away from the activation
// boundary), the exactness of the skipped avatar queries, SPD Hessians, and the factory's term selection.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "drape/collision/self_intersection.h"
#include "drape/newton/contact/avatar_contact.h"
#include "drape/newton/contact/contact_factory.h"
#include "drape/newton/contact/friction.h"
#include "drape/newton/contact/self_contact.h"
#include "drape/geometry/primitives.h"

namespace drape::collision {
namespace {

using namespace drape::newton;  // the drape's contact energies

using Eigen::VectorXd;

Eigen::MatrixXd denseHessian(const newton::Energy& e, const VectorXd& x) {
  newton::BlockMatrix h(static_cast<int>(x.size() / 3), {});
  e.addHessian(x, h);
  return Eigen::MatrixXd(h.toSparse());
}

VectorXd gradientOf(const newton::Energy& e, const VectorXd& x) {
  VectorXd g = VectorXd::Zero(x.size());
  e.addGradient(x, g);
  return g;
}

// Central differences of the value (-> gradient) and of the gradient (-> Hessian).
void expectDerivativesMatch(const newton::Energy& e, const VectorXd& x, double step, double tol) {
  const VectorXd g = gradientOf(e, x);
  const Eigen::MatrixXd H = denseHessian(e, x);
  VectorXd gFd(x.size());
  Eigen::MatrixXd hFd(x.size(), x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    VectorXd xp = x, xm = x;
    xp[i] += step;
    xm[i] -= step;
    gFd[i] = (e.value(xp) - e.value(xm)) / (2 * step);
    hFd.col(i) = (gradientOf(e, xp) - gradientOf(e, xm)) / (2 * step);
  }
  EXPECT_GT(g.norm(), 0.0);
  EXPECT_LE((g - gFd).norm(), tol * g.norm()) << "gradient\n" << g.transpose() << "\n" << gFd.transpose();
  EXPECT_LE((H - hFd).norm(), tol * H.norm()) << "Hessian";
}

double minEigenvalue(const Eigen::MatrixXd& m) {
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (m + m.transpose())).eigenvalues().minCoeff();
}

TEST(CollisionEnergyTest, AvatarContactDerivativesInFaceEdgeAndVertexRegions) {
  auto collider = std::make_shared<AvatarCollider>(makeIcosphere(Eigen::Vector3d::Zero(), 0.3, 2));
  const TriangleMesh& mesh = collider->mesh();
  // Vertices placed off a face centre, an edge midpoint and a mesh vertex, inside and outside.
  std::vector<Eigen::Vector3d> points;
  const double offsets[] = {0.004, -0.006, 0.007};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(7 * k, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(7 * k, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(7 * k, 2));
    const Eigen::Vector3d anchors[] = {(a + b + c) / 3.0, 0.5 * (a + b), a};
    for (const auto& anchor : anchors) points.push_back(anchor * (1.0 + offsets[k] / 0.3) + Eigen::Vector3d(1e-4, 2e-4, -1e-4));
  }
  VectorXd x(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i) x.segment<3>(3 * i) = points[i];
  ContactParameters params;
  params.stiffness = 50.0;
  params.thickness = 0.01;
  params.projectHessian = false;
  AvatarContactEnergy energy(collider, static_cast<int>(points.size()), params);
  EXPECT_EQ(energy.contacts(x).size(), points.size());
  expectDerivativesMatch(energy, x, 1e-7, 1e-5);

  params.projectHessian = true;
  AvatarContactEnergy projected(collider, static_cast<int>(points.size()), params);
  EXPECT_GE(minEigenvalue(denseHessian(projected, x)), -1e-9);
}

TEST(CollisionEnergyTest, AvatarContactSkippingIsExact) {
  auto collider = std::make_shared<AvatarCollider>(makeIcosphere(Eigen::Vector3d::Zero(), 0.3, 3));
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 400;
  VectorXd x0(3 * n);
  for (int v = 0; v < n; ++v) {
    Eigen::Vector3d dir(u(rng), u(rng), u(rng));
    x0.segment<3>(3 * v) = dir.normalized() * (0.3 + 0.05 * u(rng));
  }
  ContactParameters params;
  params.thickness = 0.005;
  AvatarContactEnergy lagged(collider, n, params);
  AvatarContactEnergy fresh(collider, n, params);  // never sees beginStep: queries every vertex
  newton::StepContext ctx;
  ctx.previousPositions = &x0;
  lagged.beginStep(ctx);
  for (double amplitude : {0.0, 0.002, 0.02, 0.1}) {
    const VectorXd x = x0 + amplitude * VectorXd::NullaryExpr(3 * n, [&] { return u(rng); });
    EXPECT_NEAR(lagged.value(x), fresh.value(x), 1e-14 * (1.0 + fresh.value(x)));
    EXPECT_EQ(lagged.contacts(x).size(), fresh.contacts(x).size());
    EXPECT_LE(lagged.lastQueryCount(), fresh.lastQueryCount());
  }
  EXPECT_GT(fresh.contacts(x0).size(), 50u);
}

// Step after step, beginStep queries only the vertices that may be near the sphere and keeps a lower bound for the
// others (the last distance minus the motion since). Vertices that drift inwards by 3 mm per step from 1-6 cm
// outside must come into contact exactly when an energy that queries everything says so.
TEST(CollisionEnergyTest, AvatarContactStartBoundsFollowTheMotion) {
  auto collider = std::make_shared<AvatarCollider>(makeIcosphere(Eigen::Vector3d::Zero(), 0.3, 3));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 300;
  std::vector<Eigen::Vector3d> dirs(n);
  std::vector<double> start(n);
  for (int v = 0; v < n; ++v) {
    dirs[v] = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    start[v] = 0.3 + 0.035 + 0.025 * u(rng);
  }
  auto positionsAt = [&](int step) {
    VectorXd x(3 * n);
    for (int v = 0; v < n; ++v) x.segment<3>(3 * v) = dirs[v] * std::max(0.29, start[v] - 0.003 * step);
    return x;
  };
  ContactParameters params;
  params.thickness = 0.005;
  AvatarContactEnergy stepped(collider, n, params);
  int fewestStartQueries = n, mostContacts = 0;
  for (int step = 0; step < 20; ++step) {
    const VectorXd xn = positionsAt(step);
    newton::StepContext ctx;
    ctx.previousPositions = &xn;
    stepped.beginStep(ctx);
    if (step > 0) fewestStartQueries = std::min(fewestStartQueries, stepped.lastStartQueryCount());
    const VectorXd x = positionsAt(step + 1);        // the step's end, 3 mm further in
    AvatarContactEnergy fresh(collider, n, params);  // no beginStep: queries every vertex
    ASSERT_EQ(stepped.contacts(x).size(), fresh.contacts(x).size()) << "step " << step;
    EXPECT_NEAR(stepped.value(x), fresh.value(x), 1e-12 * (1.0 + fresh.value(x))) << "step " << step;
    EXPECT_LE((gradientOf(stepped, x) - gradientOf(fresh, x)).norm(), 1e-12 * (1.0 + gradientOf(fresh, x).norm()));
    mostContacts = std::max(mostContacts, static_cast<int>(fresh.contacts(x).size()));
  }
  EXPECT_GT(mostContacts, n / 2);        // the drift brought most vertices into contact
  EXPECT_LT(fewestStartQueries, n / 2);  // and the start queries were skipped for many of them on the way
}

// Vertices beyond the search radius: those outside keep their distance as a bound and are not queried again at
// the next step starts; those deeper inside than the radius are ignored until they come within it. Both kinds,
// drifting 1 cm per step (outside ones inwards from 8-14 cm, inside ones outwards from 8-14 cm deep), must come
// into contact exactly when an energy that queries everything says so.
TEST(CollisionEnergyTest, AvatarContactFarVerticesKeepTheirBound) {
  const double radius = 0.3;
  auto collider = std::make_shared<AvatarCollider>(makeIcosphere(Eigen::Vector3d::Zero(), radius, 3));
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 200;  // even vertices outside, odd ones inside
  std::vector<Eigen::Vector3d> dirs(n);
  std::vector<double> gap(n);
  for (int v = 0; v < n; ++v) {
    dirs[v] = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    gap[v] = 0.11 + 0.03 * u(rng);
  }
  auto positionsAt = [&](int step) {
    VectorXd x(3 * n);
    for (int v = 0; v < n; ++v) {
      const double depth = std::max(0.0, gap[v] - 0.01 * step);  // towards the surface, then on it
      x.segment<3>(3 * v) = dirs[v] * (v % 2 == 0 ? radius + depth : radius - depth);
    }
    return x;
  };
  ContactParameters params;
  params.thickness = 0.005;
  ASSERT_LT(params.searchRadius, 0.07);  // every vertex starts beyond it
  AvatarContactEnergy stepped(collider, n, params);
  int mostContacts = 0;
  for (int step = 0; step < 16; ++step) {
    const VectorXd xn = positionsAt(step);
    newton::StepContext ctx;
    ctx.previousPositions = &xn;
    stepped.beginStep(ctx);
    // After the first step start, the outside vertices are queried only once they may be near: 4 cm from 8 cm.
    if (step >= 1 && step <= 3) {
      EXPECT_LE(stepped.lastStartQueryCount(), n / 2) << "step " << step;
    }
    const VectorXd x = positionsAt(step + 1);
    AvatarContactEnergy fresh(collider, n, params);
    ASSERT_EQ(stepped.contacts(x).size(), fresh.contacts(x).size()) << "step " << step;
    EXPECT_NEAR(stepped.value(x), fresh.value(x), 1e-12 * (1.0 + fresh.value(x))) << "step " << step;
    EXPECT_LE((gradientOf(stepped, x) - gradientOf(fresh, x)).norm(), 1e-12 * (1.0 + gradientOf(fresh, x).norm()));
    mostContacts = std::max(mostContacts, static_cast<int>(fresh.contacts(x).size()));
  }
  EXPECT_EQ(mostContacts, n);  // in the end all of them, from both sides
}

// Two triangles face to face a few millimetres apart plus a crossing edge: vertex-triangle and edge-edge pairs.
struct TwoLayers {
  Eigen::MatrixX3i triangles;
  VectorXd x;
};

TwoLayers twoLayers() {
  TwoLayers t;
  t.triangles.resize(3, 3);
  t.triangles << 0, 1, 2, 3, 4, 5, 6, 7, 8;
  t.x.resize(27);
  t.x << 0, 0, 0, 0.1, 0, 0.001, 0, 0.1, -0.0005,           // lower triangle
      0.02, 0.021, 0.004, 0.12, 0.03, 0.0045, 0.03, 0.13, 0.0035,  // upper triangle
      0.05, -0.01, -0.003, 0.052, 0.08, -0.0025, 0.2, 0.2, -0.02;  // an edge crossing under the lower triangle
  return t;
}

TEST(CollisionEnergyTest, SelfContactDerivatives) {
  const TwoLayers layers = twoLayers();
  ContactParameters params;
  params.stiffness = 80.0;
  params.thickness = 0.006;
  params.projectHessian = false;
  SelfContactEnergy energy(layers.triangles, 9, {}, params);
  const auto contacts = energy.contacts(layers.x);
  ASSERT_GE(contacts.size(), 3u);
  for (const auto& c : contacts) EXPECT_LT(c.distance, params.thickness);
  expectDerivativesMatch(energy, layers.x, 1e-8, 1e-5);

  params.projectHessian = true;
  SelfContactEnergy projected(layers.triangles, 9, {}, params);
  EXPECT_GE(minEigenvalue(denseHessian(projected, layers.x)), -1e-8);
  // Far apart: no energy at all.
  VectorXd apart = layers.x;
  for (int v = 3; v < 6; ++v) apart[3 * v + 2] += 1.0;
  for (int v = 6; v < 9; ++v) apart[3 * v + 2] -= 1.0;
  EXPECT_EQ(energy.value(apart), 0.0);
}

TEST(CollisionEnergyTest, SelfContactCandidatesFollowLargeMoves) {
  const TwoLayers layers = twoLayers();
  ContactParameters params;
  params.thickness = 0.006;
  SelfContactEnergy lagged(layers.triangles, 9, {}, params);
  VectorXd far = layers.x;
  for (int v = 3; v < 6; ++v) far[3 * v + 2] += 0.5;
  for (int v = 6; v < 9; ++v) far[3 * v + 2] -= 0.5;
  newton::StepContext ctx;
  ctx.previousPositions = &far;
  lagged.beginStep(ctx);  // no candidates near the far configuration
  EXPECT_EQ(lagged.candidateCount(), 0);
  SelfContactEnergy fresh(layers.triangles, 9, {}, params);
  EXPECT_GT(lagged.value(layers.x), 0.0);  // moved back into contact: candidates refreshed
  EXPECT_DOUBLE_EQ(lagged.value(layers.x), fresh.value(layers.x));
}

// Two pairs of parallel triangles 3 mm apart (below the 6 mm thickness), side by side: T0 under T1, T2 under T3.
VectorXd stackedPairs(Eigen::MatrixX3i& triangles) {
  triangles.resize(4, 3);
  triangles << 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11;
  VectorXd x(36);
  x << 0, 0, 0, 0.1, 0, 0, 0, 0.1, 0,                          // T0
      0.02, 0.02, 0.003, 0.06, 0.02, 0.003, 0.02, 0.06, 0.001,  // T1
      0.3, 0, 0, 0.4, 0, 0, 0.3, 0.1, 0,                        // T2
      0.32, 0.02, 0.003, 0.36, 0.02, 0.003, 0.32, 0.06, 0.003;  // T3
  return x;
}

TEST(CollisionEnergyTest, SelfContactKeepsItsCandidatesAcrossStepsAndExcludesNewCrossings) {
  Eigen::MatrixX3i triangles;
  const VectorXd first = stackedPairs(triangles);
  ContactParameters params;
  params.thickness = 0.006;
  SelfContactEnergy kept(triangles, 12, {}, params);
  newton::StepContext ctx;
  ctx.previousPositions = &first;
  kept.beginStep(ctx);
  ASSERT_EQ(kept.queryCount(), 1);
  ASSERT_TRUE(kept.crossings().empty());
  // The next step: T1's third corner 2.5 mm lower, through T0. No vertex moved half the margin: no new query.
  VectorXd second = first;
  second[3 * 5 + 2] -= 0.0025;
  ctx.previousPositions = &second;
  kept.beginStep(ctx);
  EXPECT_EQ(kept.queryCount(), 1);
  ASSERT_EQ(kept.crossings().size(), 1u);
  // The same energy as one that gathers its candidates afresh there: T0 and T1 take no part, T2 and T3 still repel.
  SelfContactEnergy fresh(triangles, 12, {}, params);
  fresh.beginStep(ctx);
  EXPECT_GT(fresh.value(second), 0.0);
  EXPECT_DOUBLE_EQ(kept.value(second), fresh.value(second));
  VectorXd separated = second;
  for (int v = 9; v < 12; ++v) separated[3 * v + 2] += 0.1;  // T3 lifted away: only the excluded pair is near
  EXPECT_EQ(fresh.value(separated), 0.0);
}

// Two 9 x 9 grids of 1 cm, 2 mm apart; a patch of the upper one is pushed down through the lower one, 0.8 mm a
// step, with every vertex jittered by up to 0.3 mm.
TEST(CollisionEnergyTest, SelfContactFindsEveryCrossingOfEveryStep) {
  constexpr int n = 9;
  const int perLayer = n * n;
  Eigen::MatrixX3i triangles(4 * (n - 1) * (n - 1), 3);
  VectorXd x(6 * perLayer);
  int f = 0;
  for (int layer = 0; layer < 2; ++layer) {
    const int base = layer * perLayer;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) x.segment<3>(3 * (base + i * n + j)) = Eigen::Vector3d(0.01 * i, 0.01 * j, 0.002 * layer);
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; j + 1 < n; ++j) {
        const int v = base + i * n + j;
        triangles.row(f++) << v, v + n, v + 1;
        triangles.row(f++) << v + 1, v + n, v + n + 1;
      }
  }
  ContactParameters params;
  params.thickness = 0.006;
  SelfContactEnergy energy(triangles, 2 * perLayer, {}, params);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.0003, 0.0003);
  int steps = 0, withCrossings = 0;
  for (int step = 0; step < 12; ++step, ++steps) {
    newton::StepContext ctx;
    ctx.previousPositions = &x;
    energy.beginStep(ctx);
    const auto expected = selfIntersectingPairs(x, triangles);
    EXPECT_EQ(energy.crossings(), expected) << "step " << step;
    withCrossings += !expected.empty();
    for (int v = 0; v < 2 * perLayer; ++v) {
      for (int k = 0; k < 3; ++k) x[3 * v + k] += jitter(rng);
      const int i = (v % perLayer) / n, j = v % n;
      if (v >= perLayer && i >= 3 && i <= 5 && j >= 3 && j <= 5) x[3 * v + 2] -= 0.0008;
    }
  }
  EXPECT_GE(withCrossings, 3);
  EXPECT_LT(energy.queryCount(), steps);  // some steps kept their candidates and tested only near them
}

// Two 13 x 13 grids of 1 cm, the upper 5 mm above the lower; a 5 x 5 vertex patch in the upper one's middle is pushed
// to `patchZ`. At 1 mm below the lower grid the patch has gone through it: the triangles around it cross the lower grid,
// while its middle vertex lies flat on the wrong side, 1 mm from the lower grid, wholly cut off by the crossing ring.
TEST(CollisionEnergyTest, SelfContactLeavesOutWhatACrossingCutsOff) {
  constexpr int n = 13;
  const int perLayer = n * n;
  Eigen::MatrixX3i triangles(4 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int layer = 0; layer < 2; ++layer)
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; j + 1 < n; ++j) {
        const int v = layer * perLayer + i * n + j;
        triangles.row(f++) << v, v + n, v + 1;
        triangles.row(f++) << v + 1, v + n, v + n + 1;
      }
  const int middle = perLayer + 6 * n + 6;
  const auto contactsOfTheMiddle = [&](double patchZ, std::size_t& crossings) {
    VectorXd x(6 * perLayer);
    for (int layer = 0; layer < 2; ++layer)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const bool patch = layer == 1 && i >= 4 && i <= 8 && j >= 4 && j <= 8;
          x.segment<3>(3 * (layer * perLayer + i * n + j)) =
              Eigen::Vector3d(0.01 * i + 0.001 * layer, 0.01 * j + 0.001 * layer, layer == 0 ? 0.0 : patch ? patchZ : 0.005);
        }
    ContactParameters params;
    params.thickness = 0.003;
    SelfContactEnergy energy(triangles, 2 * perLayer, {}, params);
    newton::StepContext ctx;
    ctx.previousPositions = &x;
    energy.beginStep(ctx);
    crossings = energy.crossings().size();
    int count = 0;
    for (const collision::ContactStencil& s : energy.contacts(x))
      count += static_cast<int>(std::count(s.vertices.begin(), s.vertices.begin() + s.count, middle));
    return count;
  };
  std::size_t crossings = 0;
  EXPECT_GT(contactsOfTheMiddle(0.001, crossings), 0) << "1 mm above the lower grid: in contact";
  EXPECT_EQ(crossings, 0u);
  EXPECT_EQ(contactsOfTheMiddle(-0.001, crossings), 0) << "1 mm below, through it: cut off, no contact";
  EXPECT_GT(crossings, 10u);
}

// Lagged friction contacts on 5 vertices: vertex 0 against a floor, and vertex 1 against the edges' point of
// vertices 2-4 (an edge-edge-like stencil) with a slanted normal.
std::vector<FrictionEnergy::LaggedContact> frictionContacts() {
  std::vector<FrictionEnergy::LaggedContact> contacts(2);
  contacts[0].stencil.vertices = {0, 0, 0, 0};
  contacts[0].stencil.weights = {1, 0, 0, 0};
  contacts[0].stencil.count = 1;
  contacts[0].stencil.normal = Eigen::Vector3d(0, 0, 1);
  contacts[0].normalForce = 2.0;
  contacts[1].stencil.vertices = {1, 2, 3, 4};
  contacts[1].stencil.weights = {1.0, -0.2, -0.5, -0.3};
  contacts[1].stencil.count = 4;
  contacts[1].stencil.normal = Eigen::Vector3d(1, 2, 2) / 3.0;
  contacts[1].normalForce = 0.7;
  for (auto& c : contacts) c.tangent = Eigen::Matrix3d::Identity() - c.stencil.normal * c.stencil.normal.transpose();
  return contacts;
}

TEST(CollisionEnergyTest, FrictionDerivativesStaticAndSlidingAndPsd) {
  const int n = 5;
  VectorXd start = VectorXd::LinSpaced(3 * n, 0.0, 0.1);
  const std::vector<FrictionEnergy::LaggedContact> contacts = frictionContacts();
  const double h = 1e-3;
  FrictionEnergy friction(nullptr, nullptr, FrictionParameters{0.4, 1e-3});
  friction.setLagged(contacts, start, h);  // eps = 1e-6 m
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double slip : {3e-7, 5e-5}) {  // static (below eps) and sliding
    const VectorXd x = start + slip * VectorXd::NullaryExpr(3 * n, [&] { return u(rng); });
    expectDerivativesMatch(friction, x, slip * 1e-4, 2e-4);
    EXPECT_GE(minEigenvalue(denseHessian(friction, x)), -1e-9 * denseHessian(friction, x).norm());
  }
  // Sliding force magnitude on a single vertex is mu * lambda (kinetic Coulomb).
  VectorXd x = start;
  x.segment<3>(0) += Eigen::Vector3d(1e-3, 0, 0);
  EXPECT_NEAR(gradientOf(friction, x).segment<3>(0).norm(), 0.4 * 2.0, 1e-12);
  EXPECT_NEAR(frictionF0(0.0, 1.0), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(frictionF0(1.0, 1.0), 1.0, 1e-15);
}

// At a step's first iterate friction adds its isotropic majorizer: the quadratic model with it lies above the
// friction potential everywhere and touches it at x (the half-quadratic bound of friction.h), and it is at least as
// stiff as the Hessian; the Hessian's own model is no bound while sliding (it has no curvature along the slip).
TEST(CollisionEnergyTest, FrictionMajorizerBoundsThePotentialAtThePrediction) {
  const int n = 5;
  const VectorXd start = VectorXd::LinSpaced(3 * n, 0.0, 0.1);
  const std::vector<FrictionEnergy::LaggedContact> contacts = frictionContacts();
  const double h = 1e-3;  // eps = 1e-6 m
  FrictionEnergy exact(nullptr, nullptr, FrictionParameters{0.4, 1e-3, false});
  FrictionEnergy majorized(nullptr, nullptr, FrictionParameters{0.4, 1e-3, true});
  exact.setLagged(contacts, start, h);
  majorized.setLagged(contacts, start, h);
  auto prediction = [&](const FrictionEnergy& e, const VectorXd& x, VectorXd& g) {
    newton::BlockMatrix m(n, {});
    g = VectorXd::Zero(x.size());
    e.addPredictionGradientAndHessian(x, g, m);
    return Eigen::MatrixXd(m.toSparse());
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random = [&](double scale) { return VectorXd(scale * VectorXd::NullaryExpr(3 * n, [&] { return u(rng); })); };
  for (double slip : {4e-7, 3e-5}) {  // static (below eps) and sliding
    const VectorXd x = start + random(slip);
    VectorXd g, gExact;
    const Eigen::MatrixXd M = prediction(majorized, x, g);
    const Eigen::MatrixXd H = prediction(exact, x, gExact);  // switched off: the Hessian itself
    EXPECT_LE((H - denseHessian(exact, x)).norm(), 1e-12 * H.norm());
    EXPECT_LE((g - gradientOf(exact, x)).norm(), 1e-12 * g.norm()) << "the gradient is the exact one";
    EXPECT_LE((gExact - g).norm(), 1e-12 * g.norm());
    EXPECT_GE(minEigenvalue(M - H), -1e-9 * M.norm()) << "at least as stiff as the Hessian, slip " << slip;
    double worstMajorizer = -1e300, worstHessian = -1e300;  // max of D(z) - model(z), relative to D(x)
    for (int k = 0; k < 400; ++k) {
      const VectorXd dz = random(slip * std::pow(10.0, u(rng)));  // steps from 0.1x to 10x the slip
      const double d = majorized.value(x + dz);
      worstMajorizer = std::max(worstMajorizer, d - (majorized.value(x) + g.dot(dz) + 0.5 * dz.dot(M * dz)));
      worstHessian = std::max(worstHessian, d - (majorized.value(x) + g.dot(dz) + 0.5 * dz.dot(H * dz)));
    }
    const double scale = majorized.value(x);
    EXPECT_LE(worstMajorizer, 1e-12 * scale) << "slip " << slip;
    if (slip > 1e-6) {
      EXPECT_GT(worstHessian, 1e-3 * scale) << "the Hessian's model is no bound while sliding";
    }
  }
}

TEST(CollisionEnergyTest, FactoryCreatesOnlyNeededTerms) {
  const TwoLayers layers = twoLayers();
  ContactSetup setup;
  setup.selfContact.thickness = 0.006;
  EXPECT_TRUE(makeContactEnergies(setup, 9, layers.triangles, {}).empty());
  setup.selfCollision = true;
  auto energies = makeContactEnergies(setup, 9, layers.triangles, {});
  ASSERT_EQ(energies.size(), 2u);
  EXPECT_EQ(energies[0]->name(), "self_contact");
  EXPECT_EQ(energies[1]->name(), "intersection_contour");
  setup.avatar = std::make_shared<AvatarCollider>(makeBox(Eigen::Vector3d(-1, -1, -2), Eigen::Vector3d(1, 1, -1)));
  setup.frictionCoefficient = 0.3;
  energies = makeContactEnergies(setup, 9, layers.triangles, {});
  ASSERT_EQ(energies.size(), 4u);
  EXPECT_EQ(energies[0]->name(), "avatar_contact");
  EXPECT_EQ(energies[1]->name(), "self_contact");
  EXPECT_EQ(energies[2]->name(), "intersection_contour");
  EXPECT_EQ(energies[3]->name(), "friction");
  // Friction picks up the self contacts lagged at x_n.
  newton::StepContext ctx;
  ctx.previousPositions = &layers.x;
  for (auto& e : energies) e->beginStep(ctx);
  EXPECT_GE(static_cast<const FrictionEnergy&>(*energies[3]).laggedContacts().size(), 3u);
  setup.frictionCoefficient = 0.0;
  EXPECT_EQ(makeContactEnergies(setup, 9, layers.triangles, {}).size(), 3u);
}

}  // namespace
}  // namespace drape::collision
