// Non-conforming seams in the preview solver (pd-dd section 4.4): two panels meshed at different resolutions,
// joined by edge stitches (a vertex of one side tied to a point of an edge of the other). The stitch stencil
// A = [1, -(1 - t), -t], its place in K, the domain-decomposed solve against the monolithic CHOLMOD solve, and
// a preview run that closes the seam.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <random>

#include "drape/core/input_error.h"
#include "drape/pd/dd_solver.h"
#include "drape/pd/domain_partition.h"
#include "drape/pd/grid_cloth.h"
#include "drape/pd/pd_system.h"
#include "drape/pd/preview_solver.h"
#include "drape/pd/sparse_cholesky.h"

namespace drape::pd {
namespace {

struct SeamedCloth {
  drape::model::ClothModel model;
  int leftVertices = 0;   // vertices [0, leftVertices) belong to the left panel
  int leftTriangles = 0;  // triangles [0, leftTriangles) belong to the left panel
};

// Left panel: nx1 x ny1 grid, 0.5 x 0.6 m; right panel: nx2 x ny2 grid of the same size placed `gap` metres to the
// right. Every vertex of the right panel's left column is stitched to the point at its height on the left panel's
// right column (an edge of that column, t from the heights). Pins: the left panel's top-left corner and the right
// panel's top-right corner.
SeamedCloth seamedCloth(int nx1, int ny1, int nx2, int ny2, double gap) {
  const double width = 0.5, height = 0.6;
  GridClothOptions o;
  o.width = width;
  o.height = height;
  o.pinTopCorners = false;
  o.nx = nx1;
  o.ny = ny1;
  const drape::model::ClothModel a = makeGridCloth(o);
  o.nx = nx2;
  o.ny = ny2;
  const drape::model::ClothModel b = makeGridCloth(o);
  const int na = a.numVertices(), nb = b.numVertices();
  const int ta = static_cast<int>(a.triangles.rows()), tb = static_cast<int>(b.triangles.rows());
  SeamedCloth out;
  out.leftVertices = na;
  out.leftTriangles = ta;
  drape::model::ClothModel& m = out.model;
  m.fabrics = a.fabrics;
  m.restCoords.resize(na + nb, 2);
  m.restCoords << a.restCoords, b.restCoords;
  m.positions.resize(3 * (na + nb));
  m.positions << a.positions, b.positions;
  for (int v = 0; v < nb; ++v) m.positions[3 * (na + v)] += width + gap;
  m.triangles.resize(ta + tb, 3);
  m.triangles << a.triangles, (b.triangles.array() + na).matrix();
  const double h1 = height / (ny1 - 1);
  for (int j = 0; j < ny2; ++j) {
    const double y = height * j / (ny2 - 1);
    const int e = std::min(static_cast<int>(y / h1), ny1 - 2);
    const double t = std::clamp((y - e * h1) / h1, 0.0, 1.0);
    m.edgeStitches.push_back({na + j * nx2, e * nx1 + nx1 - 1, (e + 1) * nx1 + nx1 - 1, t});
  }
  m.pinned = {(ny1 - 1) * nx1, na + nb - 1};
  return out;
}

// Distance between each edge-stitched vertex and its edge point, metres.
double maxSeamGap(const drape::model::ClothModel& m, const Eigen::VectorXd& x) {
  double gap = 0.0;
  for (const drape::model::EdgeStitch& e : m.edgeStitches) {
    const Eigen::Vector3d p = (1.0 - e.t) * x.segment<3>(3 * e.a) + e.t * x.segment<3>(3 * e.b);
    gap = std::max(gap, (x.segment<3>(3 * e.vertex) - p).norm());
  }
  return gap;
}

Eigen::SparseMatrix<double> sumOfDomains(const std::vector<DomainMatrix>& domains, int n) {
  Eigen::SparseMatrix<double> sum(n, n);
  for (const auto& dm : domains) {
    std::vector<Eigen::Triplet<double>> t;
    for (int c = 0; c < dm.k.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(dm.k, c); it; ++it)
        t.emplace_back(dm.dofs[it.row()], dm.dofs[it.col()], it.value());
    Eigen::SparseMatrix<double> p(n, n);
    p.setFromTriplets(t.begin(), t.end());
    sum += p;
  }
  return sum;
}

TEST(PdNonconforming, EdgeStitchAddsTheStencilToK) {
  const SeamedCloth sc = seamedCloth(9, 11, 6, 8, 0.02);
  const drape::model::ClothModel& m = sc.model;
  PreviewSettings s;
  s.stitchWeight = 3e4;
  PdSystem with(m, s);
  drape::model::ClothModel without = m;
  without.edgeStitches.clear();
  PdSystem bare(without, s);
  ASSERT_EQ(with.freeCount(), bare.freeCount());
  // Independent assembly of sum_s w A_s^T A_s over the free DOFs (dense, by hand).
  const int n = with.freeCount();
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(n, n);
  const auto& dof = with.dofOfVertex();
  for (const drape::model::EdgeStitch& e : m.edgeStitches) {
    const int v[3] = {e.vertex, e.a, e.b};
    const double a[3] = {1.0, -(1.0 - e.t), -e.t};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (dof[v[i]] >= 0 && dof[v[j]] >= 0) expected(dof[v[i]], dof[v[j]]) += 3e4 * a[i] * a[j];
  }
  const Eigen::MatrixXd diff = Eigen::MatrixXd(with.matrix()) - Eigen::MatrixXd(bare.matrix());
  EXPECT_LT((diff - expected).norm(), 1e-9 * expected.norm());
  // The stencil annihilates any position field that is affine along the seam: K's stitch part has a point on
  // the edge as its zero-length rest state.
  Eigen::VectorXd x(m.numVertices());
  for (int v = 0; v < m.numVertices(); ++v) x[v] = 0.3 + 2.0 * m.positions[3 * v + 1];  // affine in height
  Eigen::VectorXd xf(n);
  for (int d = 0; d < n; ++d) xf[d] = x[with.freeVertices()[d]];
  // Pinned vertices are not on the seam, so the free part alone carries the stitch terms.
  EXPECT_LT((expected * xf).norm(), 1e-9 * expected.norm() * xf.norm());
  // One extra 3-vertex stencil per edge stitch, (v, a, b) in that order, owned by a triangle of the edge.
  ASSERT_EQ(with.stencils().size(), bare.stencils().size() + m.edgeStitches.size());
  for (size_t k = 0; k < m.edgeStitches.size(); ++k) {
    const Stencil& st = with.stencils()[bare.stencils().size() + k];
    const drape::model::EdgeStitch& e = m.edgeStitches[k];
    EXPECT_EQ(st.size, 3);
    EXPECT_EQ(st.vertices[0], e.vertex);
    EXPECT_EQ(st.vertices[1], e.a);
    EXPECT_EQ(st.vertices[2], e.b);
    const Eigen::Vector3i owner = m.triangles.row(st.ownerTriangle);
    EXPECT_TRUE((owner.array() == e.a).any() && (owner.array() == e.b).any()) << "stitch " << k;
  }
}

TEST(PdNonconforming, ValidationNamesTheBadEdgeStitch) {
  SeamedCloth sc = seamedCloth(5, 5, 4, 4, 0.0);
  const int nv = sc.model.numVertices();
  auto expectError = [&](drape::model::EdgeStitch e, const std::string& fragment) {
    drape::model::ClothModel m = sc.model;
    m.edgeStitches[2] = e;
    try {
      PdSystem sys(m, PreviewSettings{});
      ADD_FAILURE() << "no error for " << fragment;
    } catch (const InputError& err) {
      EXPECT_NE(std::string(err.what()).find("edge stitch 2: " + fragment), std::string::npos) << err.what();
    }
  };
  expectError({nv, 4, 9, 0.5}, "vertex " + std::to_string(nv) + " out of range");
  expectError({26, -1, 9, 0.5}, "edge end a -1 out of range");
  expectError({26, 4, 9, 1.5}, "t = 1.5 outside [0, 1]");
  expectError({26, 4, 9, -0.1}, "t = -0.1 outside [0, 1]");
  expectError({4, 4, 9, 0.5}, "vertex 4 is an end of its own edge");
  expectError({9, 4, 9, 0.5}, "vertex 9 is an end of its own edge");
}

TEST(PdNonconforming, DomainMatricesSumToKAndTheSeamCrossesDomains) {
  const SeamedCloth sc = seamedCloth(24, 30, 17, 22, 0.0);
  const drape::model::ClothModel& m = sc.model;
  PdSystem sys(m, PreviewSettings{});
  // Hand-made partition: one domain per panel, so every edge stitch is an interface between the two.
  std::vector<int> byPanel(m.triangles.rows(), 0);
  for (int t = sc.leftTriangles; t < m.triangles.rows(); ++t) byPanel[t] = 1;
  const Eigen::MatrixXd k = Eigen::MatrixXd(sys.matrix());
  for (int d : {2, 8}) {
    const std::vector<int> part =
        d == 2 ? byPanel : partitionTriangles(m.triangles, m.numVertices(), m.stitches, m.edgeStitches, d);
    const auto domains = splitSystem(sys, part, d);
    const double diff = (Eigen::MatrixXd(sumOfDomains(domains, sys.freeCount())) - k).norm();
    EXPECT_LT(diff, 1e-12 * k.norm()) << "D = " << d;
  }
  // With the per-panel split, every stitched vertex of the right panel is also held by the left domain.
  DomainDecomposedSolver dd(splitSystem(sys, byPanel, 2), sys.freeCount());
  ASSERT_TRUE(dd.ok());
  for (const drape::model::EdgeStitch& e : m.edgeStitches)
    EXPECT_EQ(dd.dofClasses()[sys.dofOfVertex()[e.vertex]], DofClass::Duplicate) << "vertex " << e.vertex;
  EXPECT_EQ(dd.duplicateCount(), static_cast<int>(m.edgeStitches.size()));
  EXPECT_EQ(dd.cornerCount(), 0);
}

TEST(PdNonconforming, PartitionLinksTheStitchedTriangles) {
  // Two panels with a gap: without the stitches' links the triangle graph has two components.
  const SeamedCloth sc = seamedCloth(12, 14, 9, 11, 0.05);
  const drape::model::ClothModel& m = sc.model;
  // D = 1 is trivial; with D = 2 METIS on the linked graph must still give every triangle a valid domain.
  for (int d : {2, 5}) {
    const auto part = partitionTriangles(m.triangles, m.numVertices(), m.stitches, m.edgeStitches, d);
    ASSERT_EQ(part.size(), static_cast<size_t>(m.triangles.rows()));
    std::vector<int> counts(d, 0);
    for (int p : part) {
      ASSERT_GE(p, 0);
      ASSERT_LT(p, d);
      ++counts[p];
    }
    for (int c : counts) EXPECT_GT(c, 0) << "D = " << d;
  }
}

TEST(PdNonconforming, DecomposedSolveEqualsMonolithicForManyDomainCounts) {
  const SeamedCloth sc = seamedCloth(24, 30, 17, 22, 0.01);
  const drape::model::ClothModel& m = sc.model;
  PdSystem sys(m, PreviewSettings{});
  const int n = sys.freeCount();
  std::mt19937 rng(13);
  std::normal_distribution<double> normal;
  Eigen::MatrixX3d b(n, 3);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) b(i, c) = normal(rng);
  MonolithicSolver mono(sys.matrix());
  ASSERT_TRUE(mono.ok());
  Eigen::MatrixX3d xm;
  mono.solve(b, xm);
  EXPECT_LT((sys.matrix() * xm - b).norm() / b.norm(), 1e-10);
  for (int d : {1, 2, 4, 8, 16, 32}) {
    const auto part = partitionTriangles(m.triangles, m.numVertices(), m.stitches, m.edgeStitches, d);
    // Count the edge stitches whose vertex's triangles and edge lie in different domains (a non-conforming
    // interface between domains): METIS is free to cut along the seam or not, so only report it.
    int crossing = 0;
    for (const drape::model::EdgeStitch& e : m.edgeStitches) {
      const int tv = sys.incidentTriangles()[sys.incidentOffsets()[e.vertex]];
      const int te = sys.incidentTriangles()[sys.incidentOffsets()[e.a]];
      crossing += part[tv] != part[te];
    }
    for (int stride : {0, 3}) {
      DomainDecomposedSolver dd(splitSystem(sys, part, d), n, stride);
      ASSERT_TRUE(dd.ok()) << "D = " << d;
      Eigen::MatrixX3d x;
      dd.solve(b, x);
      const double rel = (x - xm).norm() / xm.norm();
      EXPECT_LT(rel, 1e-9) << "D = " << d << " stride " << stride;
      EXPECT_EQ(dd.domainCount(), d);
      if (stride == 0)
        std::printf("D = %2d: %d of %zu edge stitches cross domains, %d corners, %d duplicates, rel %.1e\n", d,
                    crossing, m.edgeStitches.size(), dd.cornerCount(), dd.duplicateCount(), rel);
    }
  }
  // Per-panel split: the whole seam is the interface.
  std::vector<int> byPanel(m.triangles.rows(), 0);
  for (int t = sc.leftTriangles; t < m.triangles.rows(); ++t) byPanel[t] = 1;
  DomainDecomposedSolver dd(splitSystem(sys, byPanel, 2), n);
  ASSERT_TRUE(dd.ok());
  EXPECT_GT(dd.duplicateCount(), 0);
  Eigen::MatrixX3d x;
  dd.solve(b, x);
  EXPECT_LT((x - xm).norm() / xm.norm(), 1e-9);
}

TEST(PdNonconforming, PreviewClosesTheSeam) {
  const double gap = 0.03;
  SeamedCloth sc = seamedCloth(16, 19, 11, 14, gap);
  drape::model::ClothModel& m = sc.model;
  // The right pin holds its corner where the closed seam puts it (the panels' rest width apart).
  m.pinTargets = {m.positions.segment<3>(3 * m.pinned[0]),
                  m.positions.segment<3>(3 * m.pinned[1]) - Eigen::Vector3d(gap, 0.0, 0.0)};
  EXPECT_NEAR(maxSeamGap(m, m.positions), gap, 1e-12);
  const int bottomRight = sc.leftVertices + 10;  // right panel (11 x 14 vertices): row 0, last column
  for (GlobalSolverKind kind : {GlobalSolverKind::DomainDecomposed, GlobalSolverKind::Monolithic}) {
    PreviewSettings s;
    s.domains = 4;
    s.globalSolver = kind;
    s.relaxationTime = 0.1;
    PreviewSolver solver(m, s);
    for (int i = 0; i < 30; ++i) ASSERT_NE(solver.step().status, PreviewStatus::Diverged) << "step " << i;
    const Eigen::VectorXd& x = solver.positions();
    ASSERT_TRUE(x.allFinite());
    const double closed = maxSeamGap(m, x);
    std::printf("%s: seam gap after 30 preview steps: %.3e m\n",
                kind == GlobalSolverKind::Monolithic ? "monolithic" : "decomposed", closed);
    EXPECT_LT(closed, 1e-3);
    for (size_t p = 0; p < m.pinned.size(); ++p)
      EXPECT_LT((x.segment<3>(3 * m.pinned[p]) - m.pinTargets[p]).norm(), 1e-12);
    // The seam closed by pulling the panels together, not by collapsing them: the bottom row keeps most of its
    // 1 m width.
    EXPECT_GT(x[3 * bottomRight] - x[0], 0.8);
  }
}

// The sewn switch (PreviewSettings::sewnGap, sewnTime): reported from the first converged step after every stitch
// gap has stayed below sewnGap for sewnTime, for good; never with sewnGap 0.
TEST(PdNonconforming, SeamCountsAsSewnOnceItStayedClosed) {
  SeamedCloth sc = seamedCloth(16, 19, 11, 14, 0.03);
  drape::model::ClothModel& m = sc.model;
  m.pinTargets = {m.positions.segment<3>(3 * m.pinned[0]),
                  m.positions.segment<3>(3 * m.pinned[1]) - Eigen::Vector3d(0.03, 0.0, 0.0)};
  PreviewSettings s;
  s.domains = 4;
  s.relaxationTime = 0.1;
  s.sewnGap = 1e-3;
  s.sewnTime = 0.05;
  PreviewSolver solver(m, s);
  double closedSince = -1.0, sewnAt = -1.0;
  for (int i = 0; i < 60; ++i) {
    const double before = solver.time();
    const PreviewReport r = solver.step();
    ASSERT_NE(r.status, PreviewStatus::Diverged) << "step " << i;
    const double gap = maxSeamGap(m, solver.positions());
    if (gap >= s.sewnGap) closedSince = -1.0;
    else if (closedSince < 0.0) closedSince = solver.time();
    if (sewnAt >= 0.0) {
      EXPECT_TRUE(r.sewn) << "step " << i << ": sewn is for good";
      continue;
    }
    if (!r.sewn) continue;
    sewnAt = solver.time();
    EXPECT_EQ(r.status, PreviewStatus::Converged);
    // The gaps were closed at the end of every step since closedSince, sewnTime before this one's end.
    ASSERT_GE(closedSince, 0.0) << "sewn with a gap of " << gap << " m";
    EXPECT_GE(solver.time() - closedSince + 1e-12, s.sewnTime) << "closed at " << closedSince << ", sewn at " << before;
  }
  ASSERT_GE(sewnAt, 0.0) << "never sewn; the seam gap ends at " << maxSeamGap(m, solver.positions());
  EXPECT_LT(sewnAt, 0.3);

  s.sewnGap = 0.0;
  PreviewSolver never(m, s);
  for (int i = 0; i < 60; ++i) EXPECT_FALSE(never.step().sewn) << "step " << i;
  EXPECT_LT(maxSeamGap(m, never.positions()), 1e-3);  // closed all the same
}

}  // namespace
}  // namespace drape::pd
