// Self-collision exclusions of non-conforming seams: an edge stitch (vertex sewn to a point of an edge) counts as a
// stitch between its vertex and the nearer end of the edge, in the preview's ClothContacts and in the Newton
// drape's SelfContactEnergy (collision::contactMergedVertices). Two panels meshed at different spacings, sewn by
// edge stitches: the merged groups directly; the contacts counted with and without the edge stitches on the seam
// closed at a right-angle fold; and a Newton drape with cloth-cloth contact that still closes the seam.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstdio>
#include <numeric>
#include <set>

#include "drape/newton/contact/contact_factory.h"
#include "drape/newton/contact/self_contact.h"
#include "drape/newton/newton_solver.h"
#include "drape/pd/cloth_collision.h"
#include "drape/pd/contact_solve.h"
#include "newton_test_cloths.h"

namespace drape {
namespace {

using drape::model::ClothModel;
using drape::model::EdgeStitch;
using newton::appendGridPanel;

constexpr int kCoarse = 6;              // coarse panel: 6 x 6 vertices (4 cm spacing)
constexpr int kFineX = 9, kFineY = 12;  // fine panel: 2.5 cm x 1.8 cm spacing (no stitch at t = 1/2)
constexpr double kSize = 0.2;           // both panels 0.2 x 0.2 m

// Coarse panel at the origin, fine panel `gap` metres to its right; every vertex of the fine panel's left column is
// edge-stitched to the point at its height on the coarse panel's right column. gap = 0: the seam is closed.
ClothModel seamedPanels(double gap) {
  ClothModel m;
  drape::model::TriangleFabric cotton;
  cotton.stretchWarp = cotton.stretchWeft = 5000.0;
  cotton.shear = 250.0;
  m.fabrics = {cotton};
  appendGridPanel(m, kCoarse, kCoarse, kSize, kSize, Eigen::Vector3d::Zero());
  appendGridPanel(m, kFineX, kFineY, kSize, kSize, Eigen::Vector3d(kSize + gap, 0.0, 0.0));
  const int base = kCoarse * kCoarse;
  const double h1 = kSize / (kCoarse - 1);
  for (int j = 0; j < kFineY; ++j) {
    const double y = kSize * j / (kFineY - 1);
    const int e = std::min(static_cast<int>(y / h1), kCoarse - 2);
    m.edgeStitches.push_back({base + j * kFineX, e * kCoarse + kCoarse - 1, (e + 1) * kCoarse + kCoarse - 1,
                              std::clamp(y / h1 - e, 0.0, 1.0)});
  }
  return m;
}

// The seam closed to within 0.8 mm with the fine panel folded up at a right angle (a box corner): the fine panel in
// the plane x = 0.2 m - 0.3 mm, from z = 0.7 mm upwards. Every fine-side seam vertex hovers 0.7 mm over a coarse
// triangle of its edge, every coarse-side seam vertex 0.3 mm in front of the fine panel's edge.
ClothModel closedFoldedSeam() {
  ClothModel m = seamedPanels(0.0);
  const int base = kCoarse * kCoarse;
  for (int v = base; v < m.numVertices(); ++v) {
    const Eigen::Vector2d r = m.restCoords.row(v).transpose();
    m.positions.segment<3>(3 * v) = Eigen::Vector3d(kSize - 0.0003, r.y(), 0.0007 + r.x());
  }
  return m;
}

Eigen::MatrixX3d rows(const Eigen::VectorXd& x) {
  Eigen::MatrixX3d out(x.size() / 3, 3);
  for (Eigen::Index v = 0; v < out.rows(); ++v) out.row(v) = x.segment<3>(3 * v).transpose();
  return out;
}

// Largest distance between an edge-stitched vertex and its edge point, metres.
double maxSeamGap(const ClothModel& m, const Eigen::VectorXd& x) {
  double gap = 0.0;
  for (const EdgeStitch& e : m.edgeStitches)
    gap = std::max(
        gap, (x.segment<3>(3 * e.vertex) - (1 - e.t) * x.segment<3>(3 * e.a) - e.t * x.segment<3>(3 * e.b)).norm());
  return gap;
}

TEST(SelfCollisionEdgeStitch, MergedVerticesPairEachStitchWithTheNearerEnd) {
  const ClothModel m = seamedPanels(0.0);
  const std::vector<std::pair<int, int>> pairs = {{1, 2}};
  const auto merged = collision::contactMergedVertices(pairs, m.edgeStitches);
  ASSERT_EQ(merged.size(), 1 + m.edgeStitches.size());
  EXPECT_EQ(merged[0], pairs[0]);
  for (size_t k = 0; k < m.edgeStitches.size(); ++k) {
    const EdgeStitch& e = m.edgeStitches[k];
    // Independent: the endpoint at the smaller distance from the stitch point, measured in the placed positions.
    const Eigen::Vector3d p = (1 - e.t) * m.positions.segment<3>(3 * e.a) + e.t * m.positions.segment<3>(3 * e.b);
    const double da = (p - m.positions.segment<3>(3 * e.a)).norm(), db = (p - m.positions.segment<3>(3 * e.b)).norm();
    EXPECT_EQ(merged[1 + k], std::make_pair(e.vertex, da <= db ? e.a : e.b)) << "edge stitch " << k;
  }
}

TEST(SelfCollisionEdgeStitch, PreviewClothContactsExcludeTheClosedSeam) {
  const ClothModel m = closedFoldedSeam();
  ASSERT_LT(maxSeamGap(m, m.positions), 1e-3);
  const int nv = m.numVertices();
  std::vector<int> dof(nv);
  std::iota(dof.begin(), dof.end(), 0);
  const pd::ClothContactOptions options{0.004, 0.01, 1e6};
  pd::ClothContacts with(m.triangles, nv, {}, dof, options, m.edgeStitches);
  pd::ClothContacts without(m.triangles, nv, {}, dof, options);

  // The stitched vertex shares its group with the nearer end of its edge, never with the farther one.
  for (const EdgeStitch& e : m.edgeStitches) {
    const int nearer = e.t <= 0.5 ? e.a : e.b, farther = e.t <= 0.5 ? e.b : e.a;
    EXPECT_EQ(with.canonical(e.vertex), with.canonical(nearer)) << "vertex " << e.vertex;
    EXPECT_NE(with.canonical(e.vertex), with.canonical(farther)) << "vertex " << e.vertex;
    EXPECT_NE(without.canonical(e.vertex), without.canonical(nearer));
  }
  // No chaining along the seam: one group per coarse-side vertex of the seam.
  std::set<int> groups;
  for (const EdgeStitch& e : m.edgeStitches) groups.insert(with.canonical(e.vertex));
  EXPECT_EQ(groups.size(), static_cast<size_t>(kCoarse));

  // Contacts on the closed seam: the two sides touch along it.
  const Eigen::MatrixX3d x = rows(m.positions);
  auto contacts = [&](pd::ClothContacts& cc) {
    cc.beginStep(x, x);
    pd::ContactAccumulator acc(nv);
    return cc.addConstraints(x, x, acc).contacts;
  };
  const int withCount = contacts(with), withoutCount = contacts(without);
  std::printf("preview contacts on the closed seam: %d without the edge stitches, %d with\n", withoutCount, withCount);
  EXPECT_GT(withoutCount, 0) << "the closed seam must touch itself for this test to mean anything";
  EXPECT_EQ(withCount, 0);
  EXPECT_LT(with.candidateCount(), without.candidateCount());
}

newton::ContactSetup selfOnly() {
  newton::ContactSetup setup;
  setup.selfCollision = true;
  setup.selfContact.thickness = 0.004;
  setup.selfContact.stiffness = 100.0;
  return setup;
}

TEST(SelfCollisionEdgeStitch, NewtonSelfContactExcludesTheClosedSeam) {
  const ClothModel m = closedFoldedSeam();
  const int nv = m.numVertices();
  auto with = newton::makeContactEnergies(selfOnly(), nv, m.triangles, {}, m.edgeStitches);
  auto without = newton::makeContactEnergies(selfOnly(), nv, m.triangles, {});
  ASSERT_EQ(with.size(), 2u);  // self_contact, intersection_contour
  ASSERT_EQ(without.size(), 2u);
  const auto* selfWith = dynamic_cast<const newton::SelfContactEnergy*>(with[0].get());
  const auto* selfWithout = dynamic_cast<const newton::SelfContactEnergy*>(without[0].get());
  ASSERT_TRUE(selfWith && selfWithout);
  const size_t nWith = selfWith->contacts(m.positions).size(), nWithout = selfWithout->contacts(m.positions).size();
  std::printf("Newton self contacts on the closed seam: %zu without the edge stitches, %zu with\n", nWithout, nWith);
  EXPECT_GT(nWithout, 0u);
  EXPECT_EQ(nWith, 0u);
  EXPECT_EQ(selfWith->value(m.positions), 0.0);
  EXPECT_GT(selfWithout->value(m.positions), 0.0);
  // The exclusion covers the seam only: a fine-panel vertex brought 1 mm over the middle of the coarse panel
  // collides.
  Eigen::VectorXd x = m.positions;
  const int fineInterior = kCoarse * kCoarse + 5 * kFineX + 4;  // middle of the fine panel
  x.segment<3>(3 * fineInterior) = Eigen::Vector3d(0.1, 0.1, 0.001);
  newton::StepContext ctx;  // a step starting there gathers the pair
  ctx.previousPositions = &x;
  with[0]->beginStep(ctx);
  EXPECT_GT(selfWith->contacts(x).size(), 0u);
}

TEST(SelfCollisionEdgeStitch, NewtonDrapeWithSelfCollisionClosesTheSeam) {
  const double gap = 0.05;
  ClothModel m = seamedPanels(gap);
  const int base = kCoarse * kCoarse;
  m.pinned = {kCoarse * (kCoarse - 1), base + kFineX * kFineY - 1};  // top outer corners, a rest width apart
  m.pinTargets = {Eigen::Vector3d(0, kSize, 0), Eigen::Vector3d(2 * kSize, kSize, 0)};
  ASSERT_NEAR(maxSeamGap(m, m.positions), gap, 1e-12);
  auto drape = [&](bool exclude) {
    auto energies = exclude
                        ? newton::makeContactEnergies(selfOnly(), m.numVertices(), m.triangles, {}, m.edgeStitches)
                        : newton::makeContactEnergies(selfOnly(), m.numVertices(), m.triangles, {});
    newton::NewtonSolver solver(m, newton::NewtonSettings{}, std::move(energies));
    bool hasSelf = false;
    for (const std::string& name : solver.energyNames()) hasSelf |= name == "self_contact";
    EXPECT_TRUE(hasSelf);
    while (solver.time() < 0.5) {
      const auto status = solver.step().status;
      EXPECT_NE(status, newton::NewtonStatus::Diverged) << "t = " << solver.time();
      if (status == newton::NewtonStatus::Diverged) break;
    }
    EXPECT_TRUE(solver.positions().allFinite());
    return solver.positions();
  };
  const Eigen::VectorXd x = drape(true);
  const double closed = maxSeamGap(m, x);
  const Eigen::VectorXd y = drape(false);
  const double blocked = maxSeamGap(m, y);
  std::printf("seam gap after a 0.5 s drape with self-collision: %.3e m (edge stitches excluded), %.3e m (not)\n",
              closed, blocked);
  EXPECT_LT(closed, 1e-3);
  // Without the exclusion the contact penalty holds the seam open by far more (it pushes the stitched vertex off
  // the triangles of its own edge).
  EXPECT_LT(closed, 0.1 * blocked);
  // Closed by pulling the panels together, not by collapsing them: the bottom row keeps most of its 0.4 m width.
  EXPECT_GT(x[3 * (base + kFineX - 1)] - x[0], 0.3);
}

}  // namespace
}  // namespace drape
