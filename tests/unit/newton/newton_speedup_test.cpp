// The production speed-ups of the Newton drape solver change nothing beyond round-off: closed-form hinge gradient
// against automatic differentiation, stencil colouring validity, assembly with the cached block map and coloured
// parallel loops against the plain serial search-based path, and whole solver runs with every switch on vs off;
// RCM reordering (valid permutation, smaller bandwidth, same matrix) and the PCG variants (fused kernels, warm
// start, mixed precision) against an independent residual and a CHOLMOD solve.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <numeric>
#include <random>
#include <map>
#include <set>

#include <tbb/task_arena.h>

#include "drape/newton/dof_ordering.h"
#include "drape/newton/hinge_bending.h"
#include "drape/newton/newton_solver.h"
#include "drape/newton/stencil_set.h"
#include "drape/newton/strain_rate_damping.h"
#include "drape/newton/stvk_membrane.h"
#include "newton_test_cloths.h"
#include "newton_test_matrices.h"

using namespace drape::newton;

namespace {

StepContext context(const Eigen::VectorXd& x0, const Eigen::VectorXd& v0, bool fast) {
  StepContext ctx{&x0, &v0, 1e-3, 0.0, 0.7, {}};
  ctx.assembly.closedFormBending = ctx.assembly.cachedBlockMap = ctx.assembly.parallel = fast;
  return ctx;
}

// Gradient and assembled Hessian of e at x, on a fresh matrix built from e's couplings.
std::pair<Eigen::VectorXd, Eigen::SparseMatrix<double>> derivatives(const Energy& e, const Eigen::VectorXd& x) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  e.addGradient(x, g);
  std::vector<std::pair<int, int>> pairs;
  e.addCouplings(pairs);
  BlockMatrix h(static_cast<int>(x.size() / 3), pairs);
  e.addHessian(x, h);
  e.addHessian(x, h);  // twice: the second pass reuses the cached slot map
  EXPECT_EQ(h.dynamicBlockCount(), 0) << e.name();
  Eigen::SparseMatrix<double> s = 0.5 * h.toSparse();
  return {g, s};
}

// Runs every assembly of e with the speed-ups off and on and compares.
void expectSameAssembly(Energy& e, const Eigen::VectorXd& x, const Eigen::VectorXd& x0, const Eigen::VectorXd& v0) {
  e.beginStep(context(x0, v0, false));
  auto [gSlow, hSlow] = derivatives(e, x);
  e.beginStep(context(x0, v0, true));
  auto [gFast, hFast] = derivatives(e, x);
  ASSERT_GT(gSlow.norm(), 0.0) << e.name();
  ASSERT_GT(hSlow.norm(), 0.0) << e.name();
  EXPECT_LT((gFast - gSlow).norm(), 1e-11 * gSlow.norm()) << e.name();
  EXPECT_LT((hFast - hSlow).norm(), 1e-11 * hSlow.norm()) << e.name();
}

}  // namespace

TEST(NewtonSpeedup, ClosedFormHingeGradientMatchesAutodiff) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  drape::model::ClothModel m = gridCloth(2, 1.0, 0.0, 1);
  HingeBending bending(m);
  ASSERT_EQ(bending.hinges().size(), 1u);
  const Hinge h = bending.hinges()[0];
  int folded = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::VectorXd x = Eigen::VectorXd::NullaryExpr(12, [&] { return u(rng); });  // arbitrary angles
    Eigen::Matrix<double, 12, 1> ad = hingeAngleGradientAutodiff(h, x), cf = hingeAngleGradient(h, x);
    EXPECT_LT((cf - ad).norm(), 1e-9 * ad.norm()) << "trial " << trial;
    double theta = 0.0;
    hingeAngleGradient(h, x, true, theta);
    EXPECT_NEAR(theta, hingeAngle(h, x), 1e-14);
    if (std::abs(theta) > 2.0) ++folded;
  }
  EXPECT_GT(folded, 10);  // the sample covers sharp folds, not just near-flat hinges
}

TEST(NewtonSpeedup, ColouringSeparatesStencilsSharingAVertex) {
  drape::model::ClothModel m = gridCloth(15, 0.01, 0.1, 2);
  HingeBending bending(m);
  std::vector<std::array<int, 4>> hinges;
  for (const auto& h : bending.hinges()) hinges.push_back(h.v);
  StencilSet<4> set(hinges);
  std::vector<int> seen(hinges.size(), 0);
  for (int c = 0; c < set.numColours(); ++c) {
    std::set<int> vertices;
    for (int s : set.colour(c)) {
      ++seen[s];
      for (int v : set[s]) EXPECT_TRUE(vertices.insert(v).second) << "colour " << c << " shares vertex " << v;
    }
  }
  for (int count : seen) EXPECT_EQ(count, 1);
  EXPECT_GT(set.numColours(), 4);  // at least the 4 vertices of one hinge need distinct neighbours
  EXPECT_LT(set.numColours(), 40);
}

// The chunk schedule of the parallel loops (contiguous runs of a local stencil order, coloured by overlapping
// vertex ranges): chunks of one colour share no vertex and every stencil is visited once. Built in an arena of 4
// threads so that the schedule exists whatever the machine's core count.
TEST(NewtonSpeedup, ChunkScheduleSeparatesChunksSharingAVertex) {
  tbb::task_arena arena(4);
  arena.execute([] {
    drape::model::ClothModel m = gridCloth(60, 0.01, 0.1, 2);
    HingeBending bending(m);
    std::vector<std::array<int, 4>> hinges;
    for (const auto& h : bending.hinges()) hinges.push_back(h.v);
    StencilSet<4> set(hinges);
    ASSERT_GE(set.numChunkColours(), 2);
    ASSERT_LE(set.numChunkColours(), 4);
    std::vector<int> seen(hinges.size(), 0);
    for (int c = 0; c < set.numChunkColours(); ++c) {
      std::map<int, int> owner;  // vertex -> chunk begin
      for (auto [begin, end] : set.chunkRanges(c))
        for (int k = begin; k < end; ++k) {
          const int s = set.serialOrder()[k];
          ++seen[s];
          for (int v : set[s]) {
            auto [it, fresh] = owner.emplace(v, begin);
            EXPECT_TRUE(fresh || it->second == begin) << "chunk colour " << c << " shares vertex " << v;
          }
        }
    }
    for (int count : seen) EXPECT_EQ(count, 1);
    // The same assembly through the chunk schedule as through the serial loop.
    Eigen::VectorXd x0 = gridCloth(60, 0.01, 0.1, 3).positions;
    Eigen::VectorXd gSerial = Eigen::VectorXd::Zero(x0.size()), gParallel = gSerial;
    HingeBending serial(m), parallel(m);
    Eigen::VectorXd v0 = Eigen::VectorXd::Zero(x0.size());
    serial.beginStep(context(m.positions, v0, false));
    parallel.beginStep(context(m.positions, v0, true));
    serial.addGradient(x0, gSerial);
    parallel.addGradient(x0, gParallel);
    EXPECT_LT((gSerial - gParallel).norm(), 1e-12 * gSerial.norm());
  });
}

// A stencil order without locality (random numbering) keeps the per-stencil colouring.
TEST(NewtonSpeedup, ChunkScheduleFallsBackWithoutLocality) {
  tbb::task_arena arena(4);
  arena.execute([] {
    drape::model::ClothModel m = gridCloth(60, 0.01, 0.1, 2);
    std::vector<int> relabel(m.numVertices());
    std::iota(relabel.begin(), relabel.end(), 0);
    std::shuffle(relabel.begin(), relabel.end(), std::mt19937(7));
    std::vector<std::array<int, 3>> triangles;
    for (Eigen::Index t = 0; t < m.triangles.rows(); ++t)
      triangles.push_back({relabel[m.triangles(t, 0)], relabel[m.triangles(t, 1)], relabel[m.triangles(t, 2)]});
    StencilSet<3> set(triangles);
    EXPECT_EQ(set.numChunkColours(), 0);
    EXPECT_GT(set.numColours(), 4);
  });
}

// The one-pass gradient + Hessian of the first Newton iteration equals the separate passes, with the speed-ups
// off and on.
TEST(NewtonSpeedup, FusedGradientAndHessianEqualSeparatePasses) {
  drape::model::ClothModel m = gridCloth(30, 0.01, 0.3, 3);
  Eigen::VectorXd x0 = gridCloth(30, 0.01, 0.3, 4).positions, v0 = Eigen::VectorXd::Zero(x0.size());
  StvkMembrane membrane(m);
  HingeBending bending(m);
  MembraneDissipation stretch(membrane.elements(), 1e-2);
  BendingDissipation bend(bending.hinges(), 1e-1);
  for (bool fast : {false, true})
    for (Energy* e : std::vector<Energy*>{&membrane, &bending, &stretch, &bend}) {
      e->beginStep(context(x0, v0, fast));
      auto [g, h] = derivatives(*e, m.positions);
      std::vector<std::pair<int, int>> pairs;
      e->addCouplings(pairs);
      BlockMatrix fused(m.numVertices(), pairs);
      Eigen::VectorXd gFused = Eigen::VectorXd::Zero(g.size());
      e->addGradientAndHessian(m.positions, gFused, fused);
      ASSERT_GT(g.norm(), 0.0) << e->name();
      EXPECT_LT((gFused - g).norm(), 1e-12 * g.norm()) << e->name() << " fast " << fast;
      EXPECT_LT((Eigen::SparseMatrix<double>(fused.toSparse()) - h).norm(), 1e-12 * h.norm()) << e->name();
    }
}

// Folding the dissipations into the membrane's and the bending's passes assembles the same gradient and Hessian
// as the four energies on their own, in the one-pass first iteration and in the separate gradient and Hessian
// passes.
TEST(NewtonSpeedup, FoldedDissipationsAssembleTheSameSum) {
  drape::model::ClothModel m = gridCloth(30, 0.01, 0.3, 3);
  Eigen::VectorXd x0 = gridCloth(30, 0.01, 0.3, 4).positions, v0 = Eigen::VectorXd::Zero(x0.size());
  StvkMembrane membrane(m);
  HingeBending bending(m);
  MembraneDissipation stretch(membrane.elements(), 1e-2);
  BendingDissipation bend(bending.hinges(), 1e-1);
  std::vector<Energy*> energies{&membrane, &bending, &stretch, &bend};
  std::vector<std::pair<int, int>> pairs;
  for (Energy* e : energies) e->addCouplings(pairs);
  auto assemble = [&](bool fold, Eigen::VectorXd& g, Eigen::VectorXd& gAlone, Eigen::SparseMatrix<double>& hFirst,
                      Eigen::SparseMatrix<double>& hLater) {
    membrane.foldDissipation(fold ? &stretch : nullptr);
    bending.foldDissipation(fold ? &bend : nullptr);
    stretch.setFolded(fold);
    bend.setFolded(fold);
    for (Energy* e : energies) e->beginStep(context(x0, v0, true));
    BlockMatrix first(m.numVertices(), pairs), later(m.numVertices(), pairs);
    g = Eigen::VectorXd::Zero(x0.size());
    for (Energy* e : energies) e->addGradientAndHessian(m.positions, g, first);
    for (Energy* e : energies) e->addHessian(m.positions, later);
    gAlone = Eigen::VectorXd::Zero(x0.size());
    for (Energy* e : energies) e->addGradient(m.positions, gAlone);
    hFirst = first.toSparse();
    hLater = later.toSparse();
  };
  Eigen::VectorXd g0, g1, gAlone0, gAlone1;
  Eigen::SparseMatrix<double> first0, later0, first1, later1;
  assemble(false, g0, gAlone0, first0, later0);
  assemble(true, g1, gAlone1, first1, later1);
  ASSERT_GT(g0.norm(), 0.0);
  EXPECT_LT((g1 - g0).norm(), 1e-12 * g0.norm());
  EXPECT_LT((gAlone0 - g0).norm(), 1e-12 * g0.norm());
  EXPECT_LT((gAlone1 - g0).norm(), 1e-12 * g0.norm());
  EXPECT_LT((first1 - first0).norm(), 1e-12 * first0.norm());
  EXPECT_LT((later1 - later0).norm(), 1e-12 * later0.norm());
  EXPECT_LT((later0 - first0).norm(), 1e-12 * first0.norm());
  // Folded, the dissipations alone add nothing to the matrix or the gradient (their share comes through the
  // partners).
  BlockMatrix alone(m.numVertices(), pairs);
  stretch.addHessian(m.positions, alone);
  bend.addHessian(m.positions, alone);
  EXPECT_EQ(alone.toSparse().norm(), 0.0);
  Eigen::VectorXd gDissipation = Eigen::VectorXd::Zero(x0.size());
  stretch.addGradient(m.positions, gDissipation);
  bend.addGradient(m.positions, gDissipation);
  EXPECT_EQ(gDissipation.norm(), 0.0);
}

// The dissipations keep x_n compactly (F_n per triangle; per hinge the angle gradient with an offset, taken from
// the bending's recorded gradient pass when that was at x_n): their values and gradients against the definition
// E = 0.5 (J d)^T W (J d), J formed at x_n from scratch, and the same dissipation with and without the recording.
TEST(NewtonSpeedup, CompactLaggedDissipationsMatchTheirDefinition) {
  drape::model::ClothModel m = gridCloth(12, 0.02, 0.3, 3);
  const Eigen::VectorXd xn = gridCloth(12, 0.02, 0.3, 4).positions, v0 = Eigen::VectorXd::Zero(xn.size());
  const Eigen::VectorXd& x = m.positions;
  const double h = 1e-3, scale = 0.7, betaS = 1e-2, betaB = 1e-1;
  StvkMembrane membrane(m);
  HingeBending bending(m);
  MembraneDissipation stretch(membrane.elements(), betaS);
  BendingDissipation computed(bending.hinges(), betaB), reused(bending.hinges(), betaB);
  bending.setRecordAngleGradients(true);
  reused.setGradientSource(&bending);
  const StepContext ctx = context(xn, v0, true);
  bending.beginStep(ctx);
  stretch.beginStep(ctx);

  // Stretch: sum over triangles of 0.5 (J d)^T W (J d).
  double expected = 0.0;
  Eigen::VectorXd expectedGradient = Eigen::VectorXd::Zero(x.size());
  for (const MembraneElement& e : membrane.elements()) {
    const Eigen::Matrix<double, 3, 9> j = greenStrainJacobian(e, xn);
    Eigen::Matrix<double, 9, 1> d;
    for (int k = 0; k < 3; ++k) d.segment<3>(3 * k) = x.segment<3>(3 * e.v[k]) - xn.segment<3>(3 * e.v[k]);
    const Eigen::Vector3d w = (betaS * scale / h * e.area) * Eigen::Vector3d(e.kWarp, e.kWeft, 2.0 * e.kShear);
    const Eigen::Vector3d rate = j * d;
    expected += 0.5 * rate.dot(w.cwiseProduct(rate));
    const Eigen::Matrix<double, 9, 1> ge = j.transpose() * w.cwiseProduct(rate);
    for (int k = 0; k < 3; ++k) expectedGradient.segment<3>(3 * e.v[k]) += ge.segment<3>(3 * k);
  }
  ASSERT_GT(expected, 0.0);
  EXPECT_NEAR(stretch.value(x), expected, 1e-12 * expected);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  stretch.addGradient(x, g);
  EXPECT_LT((g - expectedGradient).norm(), 1e-12 * expectedGradient.norm());
  // F_n taken over from the membrane's gradient pass: only when that pass ran at x_n, and only once.
  MembraneDissipation stretchReused(membrane.elements(), betaS);
  stretchReused.setStartSource(&membrane);
  membrane.setRecordDeformationGradients(true);
  membrane.beginStep(ctx);
  Eigen::VectorXd scratch = Eigen::VectorXd::Zero(x.size());
  membrane.addGradient(x, scratch);  // records at x, not at x_n
  std::vector<Eigen::Matrix<double, 3, 2>> taken;
  EXPECT_FALSE(membrane.takeRecordedDeformationGradients(xn, taken));
  stretchReused.beginStep(ctx);
  EXPECT_NEAR(stretchReused.value(x), expected, 1e-12 * expected) << "recorded at another x: recomputed";
  membrane.addGradient(xn, scratch);  // the accepted state of a step
  stretchReused.beginStep(ctx);
  EXPECT_FALSE(membrane.takeRecordedDeformationGradients(xn, taken)) << "taken over by the dissipation";
  EXPECT_NEAR(stretchReused.value(x), expected, 1e-12 * expected) << "recorded at x_n";
  Eigen::VectorXd gReusedStretch = Eigen::VectorXd::Zero(x.size());
  stretchReused.addGradient(x, gReusedStretch);
  EXPECT_LT((gReusedStretch - expectedGradient).norm(), 1e-12 * expectedGradient.norm());

  // Bending: sum over hinges of 0.5 c (grad phi(x_n) . d)^2, with the gradients computed (no recording yet,
  // then recorded at another x) and recorded at x_n.
  double expectedBend = 0.0;
  for (const Hinge& hg : bending.hinges()) {
    double phi = 0.0;
    const Eigen::Matrix<double, 12, 1> gn = hingeBendGradient(hg, xn, true, phi);
    double rate = 0.0;
    for (int k = 0; k < 4; ++k) rate += gn.segment<3>(3 * k).dot(x.segment<3>(3 * hg.v[k]) - xn.segment<3>(3 * hg.v[k]));
    expectedBend += 0.5 * (betaB * scale / h * hg.stiffness) * rate * rate;
  }
  ASSERT_GT(expectedBend, 0.0);
  computed.beginStep(ctx);
  EXPECT_NEAR(computed.value(x), expectedBend, 1e-10 * expectedBend);
  Eigen::VectorXd unused = Eigen::VectorXd::Zero(x.size());
  bending.addGradient(x, unused);  // records at x, not at x_n
  EXPECT_FALSE(bending.hasRecordedGradientsAt(xn, true));
  reused.beginStep(ctx);
  EXPECT_NEAR(reused.value(x), expectedBend, 1e-10 * expectedBend) << "recorded at another x: recomputed";
  bending.addGradient(xn, unused);  // the accepted state of a step
  ASSERT_TRUE(bending.hasRecordedGradientsAt(xn, true));
  EXPECT_FALSE(bending.hasRecordedGradientsAt(xn, false)) << "recorded in closed form";
  reused.beginStep(ctx);
  EXPECT_FALSE(bending.hasRecordedGradientsAt(xn, true)) << "taken over by the dissipation";
  EXPECT_NEAR(reused.value(x), expectedBend, 1e-10 * expectedBend) << "recorded at x_n";
  Eigen::VectorXd gComputed = Eigen::VectorXd::Zero(x.size()), gReused = Eigen::VectorXd::Zero(x.size());
  computed.addGradient(x, gComputed);
  reused.addGradient(x, gReused);
  ASSERT_GT(gComputed.norm(), 0.0);
  EXPECT_LT((gReused - gComputed).norm(), 1e-12 * gComputed.norm());
}

// A step's first Newton iterate x_n + h v_n is never its accepted state, so the gradient there (addGuessGradient)
// is the full gradient, dissipations included, but leaves the records of the last pass for the next step's x_n: the
// deformation gradients, the angle gradients and the step-start gradient.
TEST(NewtonSpeedup, GuessGradientKeepsTheLastPassRecords) {
  drape::model::ClothModel m = gridCloth(12, 0.02, 0.3, 3);
  const Eigen::VectorXd xn = gridCloth(12, 0.02, 0.3, 4).positions, v0 = Eigen::VectorXd::Zero(xn.size());
  const Eigen::VectorXd& guess = m.positions;
  const StepContext ctx = context(xn, v0, true);
  StvkMembrane membrane(m);
  HingeBending bending(m);
  MembraneDissipation stretch(membrane.elements(), 1e-2);
  BendingDissipation bend(bending.hinges(), 1e-1);
  membrane.foldDissipation(&stretch);
  membrane.setRecordDeformationGradients(true);
  membrane.setRecordStepStartGradient(true);
  stretch.setFolded(true);
  bending.foldDissipation(&bend);
  bending.setRecordAngleGradients(true);
  bending.setRecordStepStartGradient(true);
  bend.setFolded(true);
  for (Energy* e : std::vector<Energy*>{&membrane, &bending, &stretch, &bend}) e->beginStep(ctx);
  for (const Energy* e : std::vector<const Energy*>{&membrane, &bending}) {
    Eigen::VectorXd atStart = Eigen::VectorXd::Zero(xn.size());
    e->addGradient(xn, atStart);  // the last step's accepted line-search pass, at x_n
    Eigen::VectorXd full = Eigen::VectorXd::Zero(xn.size()), atGuess = Eigen::VectorXd::Zero(xn.size());
    e->addGradient(guess, full);
    e->addGradient(xn, atStart);  // recorded at x_n again
    e->addGuessGradient(guess, atGuess);
    ASSERT_GT(full.norm(), 0.0) << e->name();
    EXPECT_TRUE(atGuess == full) << e->name() << ": the same gradient, bit for bit";
    Eigen::VectorXd recorded = Eigen::VectorXd::Zero(xn.size());
    EXPECT_TRUE(e->addRecordedStepStartGradient(xn, recorded)) << e->name() << ": the record at x_n survives";
    EXPECT_FALSE(e->addRecordedStepStartGradient(guess, recorded)) << e->name() << ": nothing recorded at the guess";
  }
  std::vector<Eigen::Matrix<double, 3, 2>> taken;
  EXPECT_FALSE(membrane.takeRecordedDeformationGradients(guess, taken));
  EXPECT_TRUE(membrane.takeRecordedDeformationGradients(xn, taken));
  EXPECT_FALSE(bending.hasRecordedGradientsAt(guess, true));
  EXPECT_TRUE(bending.hasRecordedGradientsAt(xn, true));
}

TEST(NewtonSpeedup, FastAssemblyEqualsSerialSearchAssembly) {
  drape::model::ClothModel m = gridCloth(30, 0.01, 0.3, 3);  // 841 vertices: colours large enough to run in parallel chunks
  Eigen::VectorXd x0 = gridCloth(30, 0.01, 0.3, 4).positions, v0 = Eigen::VectorXd::Zero(x0.size());
  StvkMembrane membrane(m);
  expectSameAssembly(membrane, m.positions, x0, v0);
  HingeBending bending(m);
  expectSameAssembly(bending, m.positions, x0, v0);
  MembraneDissipation stretch(membrane.elements(), 1e-2);
  expectSameAssembly(stretch, m.positions, x0, v0);
  BendingDissipation bend(bending.hinges(), 1e-1);
  expectSameAssembly(bend, m.positions, x0, v0);
}

TEST(NewtonSpeedup, SolverResultsIndependentOfSwitches) {
  const int n = 12;
  drape::model::ClothModel m = hangingGridCloth(n, 0.0, 5);
  Eigen::VectorXd reference;
  for (int config = 0; config < 2; ++config) {
    NewtonSettings s;
    s.relaxation = false;
    s.closedFormBending = s.cachedBlockMap = s.parallelAssembly = s.foldDissipation = s.batchedGradients = config == 1;
    NewtonSolver solver(m, s);
    for (int k = 0; k < 30; ++k) ASSERT_EQ(solver.step().status, NewtonStatus::Converged);
    ASSERT_GT((solver.positions() - m.positions).norm(), 1e-3);  // the cloth has moved
    if (config == 0)
      reference = solver.positions();
    else
      EXPECT_LT((solver.positions() - reference).norm(), 1e-8 * reference.norm());
  }
}

// Relaxation steps take their first membrane and bending gradient from the last step's accepted line-search pass
// (NewtonSettings::stepStartGradients): the same trajectory as evaluating it afresh, through the stiffness ramp,
// fresh and reused Hessians; and the record is really used (the first passes it saves are not run).
TEST(NewtonSpeedup, RecordedStepStartGradientsGiveTheSameRelaxation) {
  const int n = 15;
  drape::model::ClothModel m = hangingGridCloth(n, 0.05, 5);
  Eigen::VectorXd reference;
  for (int config = 0; config < 2; ++config) {
    NewtonSettings s;
    s.hMax = 4e-3;  // relaxation held at 2.5e-4 s: 400 steps; run 60 of them (fresh and reused Hessians)
    s.relaxationHoldStep = true;
    s.relaxationGuess = false;  // steps starting at x_n, where the record applies (the guess starts elsewhere)
    s.stepStartGradients = config == 1;
    NewtonSolver solver(m, s);
    int reused = 0, recorded = 0;
    for (int k = 0; k < 60; ++k) {
      const NewtonStepReport r = solver.step();
      ASSERT_EQ(r.status, NewtonStatus::Converged);
      ASSERT_TRUE(r.relaxing);
      reused += r.hessianReused;
      recorded += r.recordedGradients;
    }
    EXPECT_GT(reused, 20);
    if (config == 0)
      EXPECT_EQ(recorded, 0);
    else
      EXPECT_GE(recorded, 2 * 50) << "membrane and bending from the record in (nearly) every step";
    ASSERT_GT((solver.positions() - m.positions).norm(), 1e-4);  // the cloth has moved
    if (config == 0)
      reference = solver.positions();
    else
      EXPECT_LT((solver.positions() - reference).norm(), 1e-10 * reference.norm());
  }
  // The recorded gradient itself: at the recorded x (rescaled to the current stiffness scale), not elsewhere.
  StvkMembrane membrane(m);
  HingeBending bending(m);
  const Eigen::VectorXd& x = m.positions;
  const Eigen::VectorXd x1 = gridCloth(n, 1.0 / (n - 1), 0.05, 6).positions, v0 = Eigen::VectorXd::Zero(x.size());
  for (Energy* e : std::vector<Energy*>{&membrane, &bending}) {
    StepContext ctx = context(x, v0, true);
    e->beginStep(ctx);
    e->setRecordStepStartGradient(true);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size()), r = Eigen::VectorXd::Zero(x.size());
    EXPECT_FALSE(e->addRecordedStepStartGradient(x, r)) << e->name() << ": nothing recorded yet";
    e->addGradient(x, g);
    ctx.stiffnessScale = 0.35;  // half the scale of context()
    e->beginStep(ctx);
    ASSERT_TRUE(e->addRecordedStepStartGradient(x, r)) << e->name();
    ASSERT_GT(g.norm(), 0.0);
    EXPECT_LT((r - 0.5 * g).norm(), 1e-14 * g.norm()) << e->name();
    EXPECT_FALSE(e->addRecordedStepStartGradient(x1, r)) << e->name() << ": recorded at another x";
  }
}

// ---------------------------------------------------------------------------------------------------------------
// DOF reordering (6.4), fused / warm-started / mixed-precision PCG.

namespace {

bool isPermutation(const std::vector<int>& order, int n) {
  if (static_cast<int>(order.size()) != n) return false;
  std::vector<int> seen(n, 0);
  for (int v : order) {
    if (v < 0 || v >= n || seen[v]++) return false;
  }
  return true;
}

}  // namespace

TEST(NewtonSpeedup, RcmIsPermutationAndShrinksGridBandwidth) {
  const int n = 30;
  const auto pairs = shuffledGridCouplings(n, 7);
  const auto adj = adjacencyLists(n * n, pairs);
  const std::vector<int> order = reverseCuthillMcKee(adj);
  ASSERT_TRUE(isPermutation(order, n * n));
  const std::vector<int> position = invertPermutation(order);
  for (int k = 0; k < n * n; ++k) EXPECT_EQ(position[order[k]], k);
  const int before = graphBandwidth(adj), after = graphBandwidth(adj, position);
  EXPECT_GT(before, n * n / 2);  // the shuffle spreads neighbours over the whole numbering
  // A level-set ordering of an n x n grid with diagonals needs about n + 1; allow a little slack.
  EXPECT_LE(after, n + 3) << "bandwidth before " << before;
  EXPECT_GE(after, n);  // cannot beat the grid's own bound (a row's neighbours lie a whole level away)

  // Several components and an isolated node: still a permutation, each component numbered contiguously.
  std::vector<std::pair<int, int>> two = {{0, 2}, {2, 4}, {1, 3}, {3, 5}, {5, 7}};
  const std::vector<int> o2 = reverseCuthillMcKee(adjacencyLists(9, two));
  ASSERT_TRUE(isPermutation(o2, 9));
  const std::vector<int> p2 = invertPermutation(o2);
  EXPECT_EQ(std::abs(p2[0] - p2[4]), 2);  // the path 0-2-4 occupies three consecutive positions
  EXPECT_EQ(std::abs(p2[1] - p2[7]), 3);  // the path 1-3-5-7 four
}

TEST(NewtonSpeedup, ReorderedBlockMatrixIsTheSameMatrix) {
  const int n = 25;
  const auto pairs = shuffledGridCouplings(n, 8);
  BlockMatrix plain(n * n, pairs, false), reordered(n * n, pairs, true);
  ASSERT_TRUE(reordered.reordered());
  EXPECT_EQ(plain.staticBlockCount(), reordered.staticBlockCount());
  EXPECT_LE(reordered.bandwidth(), n + 3);
  EXPECT_GT(plain.bandwidth(), 10 * reordered.bandwidth());
  fillSpd(plain, pairs, 9);
  fillSpd(reordered, pairs, 9);
  plain.addDynamicBlock(3, 400, Eigen::Matrix3d::Identity());  // a contact outside the pattern
  reordered.addDynamicBlock(3, 400, Eigen::Matrix3d::Identity());
  const Eigen::SparseMatrix<double> sp = plain.toSparse(), sr = reordered.toSparse();
  EXPECT_EQ((sp - sr).norm(), 0.0);
  for (int i : {0, 17, 624}) EXPECT_EQ((plain.diagonalBlock(i) - reordered.diagonalBlock(i)).norm(), 0.0);
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(3 * n * n, -1.0, 2.0);
  EXPECT_LT((reordered * x - sp * x).norm(), 1e-12 * (sp * x).norm());
  Eigen::VectorXd xi, back;
  reordered.toInternal(x, xi);
  reordered.toOriginal(xi, back);
  EXPECT_EQ((back - x).norm(), 0.0);
  EXPECT_EQ(xi.segment<3>(3 * reordered.internalIndex(5)), x.segment<3>(15));
}

TEST(NewtonSpeedup, PcgVariantsMeetTheToleranceAndAgreeWithCholmod) {
  const int n = 40;  // 1600 block rows: several parallel chunks in the fused kernels
  const auto pairs = shuffledGridCouplings(n, 10);
  Eigen::VectorXd b(3 * n * n);
  for (Eigen::Index k = 0; k < b.size(); ++k) b(k) = std::sin(0.37 * (k + 1));
  BlockMatrix ref(n * n, pairs, false);
  fillSpd(ref, pairs, 11);
  const Eigen::SparseMatrix<double> s = ref.toSparse();
  LinearSolveOptions direct;
  direct.kind = LinearSolverKind::Cholmod;
  Eigen::VectorXd exact;
  ASSERT_TRUE(solveLinear(ref, b, exact, direct).ok);
  ASSERT_LT((s * exact - b).norm(), 1e-10 * b.norm());
  for (bool reorder : {false, true})
    for (bool fused : {false, true})
      for (bool mixed : {false, true})
        for (Preconditioner pre : {Preconditioner::BlockJacobi, Preconditioner::Diagonal, Preconditioner::None}) {
          BlockMatrix a(n * n, pairs, reorder);
          fillSpd(a, pairs, 11);
          LinearSolveOptions o;
          o.fusedKernels = fused;
          o.mixedPrecision = mixed;
          o.preconditioner = pre;
          o.tolerance = mixed ? 1e-5 : 1e-10;
          Eigen::VectorXd x;
          const LinearSolveResult r = solveLinear(a, b, x, o);
          const std::string what = "reorder " + std::to_string(reorder) + " fused " + std::to_string(fused) +
                                   " mixed " + std::to_string(mixed) + " pre " + std::to_string(int(pre));
          ASSERT_TRUE(r.ok) << what;
          EXPECT_GT(r.iterations, 3) << what;
          const double trueResidual = (s * x - b).norm() / b.norm();  // independent of the solver's own report
          EXPECT_NEAR(r.relativeResidual, trueResidual, 1e-9 + 1e-3 * trueResidual) << what;
          EXPECT_LT(trueResidual, mixed ? 2e-5 : 1e-9) << what;
          EXPECT_LT((x - exact).norm(), (mixed ? 1e-4 : 1e-8) * exact.norm()) << what;
        }
}

TEST(NewtonSpeedup, WarmStartNeedsFewerIterations) {
  const int n = 30;
  const auto pairs = shuffledGridCouplings(n, 12);
  // Graph Laplacian + small shift: SPD and ill-conditioned like a cloth stiffness matrix (many PCG iterations).
  BlockMatrix a(n * n, pairs, true);
  for (const auto& [i, j] : pairs) {
    a.addBlock(i, j, -Eigen::Matrix3d::Identity());
    a.addBlock(i, i, Eigen::Matrix3d::Identity());
    a.addBlock(j, j, Eigen::Matrix3d::Identity());
  }
  for (int i = 0; i < n * n; ++i) a.addBlock(i, i, 1e-3 * Eigen::Matrix3d::Identity());
  Eigen::VectorXd b(3 * n * n);
  for (Eigen::Index k = 0; k < b.size(); ++k) b(k) = std::cos(0.11 * (k + 1));
  for (bool fused : {false, true}) {
    LinearSolveOptions o;
    o.fusedKernels = fused;
    o.tolerance = 1e-8;
    Eigen::VectorXd exact;
    const LinearSolveResult cold = solveLinear(a, b, exact, o);  // x empty: cold start
    ASSERT_TRUE(cold.ok);
    // Guesses 1 % and 1e-5 off the solution: the warm solves meet the same tolerance in fewer iterations, the
    // better guess in clearly fewer.
    Eigen::VectorXd x = 1.01 * exact;
    const LinearSolveResult warm = solveLinear(a, b, x, o);
    ASSERT_TRUE(warm.ok);
    EXPECT_LT(warm.relativeResidual, 1e-8);
    EXPECT_LT(warm.iterations, cold.iterations * 9 / 10) << "cold " << cold.iterations;
    x = (1.0 + 1e-5) * exact;
    const LinearSolveResult close = solveLinear(a, b, x, o);
    EXPECT_LT(close.relativeResidual, 1e-8);
    EXPECT_LT(close.iterations, cold.iterations * 2 / 3) << "cold " << cold.iterations;
    // The solution itself as the guess: no iteration at all; warm start off: the guess is ignored.
    x = exact;
    EXPECT_EQ(solveLinear(a, b, x, o).iterations, 0);
    o.warmStart = false;
    x = exact;
    EXPECT_EQ(solveLinear(a, b, x, o).iterations, cold.iterations);
  }
}

TEST(NewtonSpeedup, SolverSwitchesReachTheSameState) {
  const int n = 25;  // 625 vertices: the fused kernels run in two parallel chunks
  drape::model::ClothModel m = hangingGridCloth(n, 0.0, 14);
  auto run = [&m](const std::function<void(NewtonSettings&)>& configure) {
    NewtonSettings s;
    s.relaxation = false;
    configure(s);
    NewtonSolver solver(m, s);
    for (int k = 0; k < 25; ++k) EXPECT_EQ(solver.step().status, NewtonStatus::Converged);
    return Eigen::VectorXd(solver.positions());
  };
  // Reference: every new switch off, tight PCG tolerance; and the same at the default tau_cg = 1e-2.
  auto allOff = [](NewtonSettings& s) {
    s.reorderDofs = s.linear.warmStart = s.linear.fusedKernels = s.linear.mixedPrecision = false;
    s.coarseAggregate = 0;
    s.coupledThreshold = 0.0;
  };
  const Eigen::VectorXd ref = run([&](NewtonSettings& s) {
    allOff(s);
    s.linear.tolerance = 1e-10;
  });
  const Eigen::VectorXd off = run(allOff);
  const double moved = (ref - m.positions).norm();
  ASSERT_GT(moved, 1e-2);
  // What the PCG tolerance alone changes (a few tenths of a percent of the motion over 25 steps).
  const double cgEffect = (off - ref).norm();
  EXPECT_LT(cgEffect, 2e-2 * moved);
  // Exact reformulations (same PCG iterates up to round-off): reordering and the fused kernels, alone and together,
  // at the tight and at the default tolerance.
  for (double tol : {1e-10, 1e-2}) {
    const Eigen::VectorXd base = tol < 1e-3 ? ref : off;
    for (int mask = 1; mask < 4; ++mask) {
      const Eigen::VectorXd x = run([&](NewtonSettings& s) {
        allOff(s);
        s.reorderDofs = mask & 1;
        s.linear.fusedKernels = mask & 2;
        s.linear.tolerance = tol;
      });
      EXPECT_LT((x - base).norm(), 1e-7 * moved) << "reorder " << (mask & 1) << " fused " << (mask & 2) << " tol " << tol;
    }
  }
  // Warm start, mixed precision, the two-level preconditioner and the coupled groups change the PCG iterates within
  // its tolerance: each alone, all together and the defaults end no further from the tight reference than the
  // all-off run at the same tolerance (+50 %).
  std::vector<std::pair<std::string, std::function<void(NewtonSettings&)>>> configs = {
      {"warm", [&](NewtonSettings& s) { allOff(s), s.linear.warmStart = true; }},
      {"mixed", [&](NewtonSettings& s) { allOff(s), s.linear.mixedPrecision = true; }},
      {"coarse", [&](NewtonSettings& s) { allOff(s), s.linear.fusedKernels = true, s.coarseAggregate = 16; }},
      {"coupled", [&](NewtonSettings& s) { allOff(s), s.linear.fusedKernels = true, s.coupledThreshold = 0.6; }},
      {"all on", [](NewtonSettings& s) { s.linear.mixedPrecision = true; }},
      {"defaults", [](NewtonSettings&) {}},
  };
  std::printf("  all off  |x - x_ref| / |x_ref - x0| = %.2e\n", cgEffect / moved);
  for (const auto& [name, configure] : configs) {
    const Eigen::VectorXd x = run(configure);
    const double diff = (x - ref).norm();
    EXPECT_LT(diff, 1.5 * cgEffect) << name;
    std::printf("  %-8s |x - x_ref| / |x_ref - x0| = %.2e\n", name.c_str(), diff / moved);
  }
}
