// Speed of the collision-aware global solve (pd-dd section 6, issue 6): the dual solved by conjugate gradients
// preconditioned by K_cc (DualCgThenPcg), the warm start from the last contact forces, and the contact-set churn
// count. Each solve is checked against an independent sparse LDL^T of K + Delta K.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "drape/collision/avatar_collider.h"
#include "drape/geometry/primitives.h"
#include "drape/pd/avatar_collision.h"
#include "drape/pd/contact_solve.h"
#include "drape/pd/global_solver.h"
#include "drape/pd/grid_cloth.h"
#include "drape/pd/pd_system.h"
#include "drape/pd/preview_solver.h"
#include "pd_contact_problem.h"

namespace drape::pd {
namespace {

// A 41 x 41 cloth whose collision-free solve sinks `sink` metres with a dense contact patch of radius `patch`.
using Problem = test::ContactProblem;
Problem makeProblem(double sink, double patch) { return test::makeContactProblem(41, sink, patch); }
Eigen::MatrixX3d direct(const Problem& p) { return test::directContactSolution(p); }

// Collision-free solves a contact solve made: one per dual update and per PCG iteration, plus the warm start's.
int solvesOf(const ContactSolveStats& s) { return s.sdIterations + s.pcgIterations + (s.warmRelativeResidual < 1.0); }

TEST(PdContactSpeed, DualCgReachesTheDirectSolutionWithFewerSolvesThanThePaperSolve) {
  const Problem p = makeProblem(0.05, 0.25);
  ASSERT_GT(p.contacts.size(), 300);
  const Eigen::MatrixX3d reference = direct(p);
  Eigen::MatrixX3d free;
  p.solver->solve(p.b, free);
  const double scale = reference.norm();

  Eigen::MatrixX3d xPaper = free, xPcg = free, xDual = free;
  const ContactSolveStats paper = solveWithContacts(p.system->matrix(), *p.solver, p.contacts,
                                                    ContactSolveKind::DualThenPcg, 3000, 1e-8, xPaper, 1);
  const ContactSolveStats pcg =
      solveWithContacts(p.system->matrix(), *p.solver, p.contacts, ContactSolveKind::Pcg, 3000, 1e-8, xPcg);
  const ContactSolveStats dual = solveWithContacts(p.system->matrix(), *p.solver, p.contacts,
                                                   ContactSolveKind::DualCgThenPcg, 3000, 1e-8, xDual, 1, nullptr, 3000);
  std::printf("[ PdContactSpeed ] %d contacts, relative residual 1e-8: SD + PCG %d + %d solves, PCG %d, "
              "dual CG %d + %d\n", p.contacts.size(), paper.sdIterations, paper.pcgIterations, pcg.pcgIterations,
              dual.sdIterations, dual.pcgIterations);
  EXPECT_LT(dual.relativeResidual, 1e-8);
  EXPECT_LT((xDual - reference).norm(), 1e-5 * scale);
  EXPECT_LT((xPaper - reference).norm(), 1e-5 * scale);
  // The held vertices end on their targets up to the contact compliance (force / 1e6 N/m, < 0.5 mm here), as in
  // the direct solution.
  for (int k = 0; k < p.contacts.size(); ++k) {
    EXPECT_LT((xDual.row(p.contacts.dofs[k]) - p.contacts.targets.row(k)).norm(), 5e-4);
    EXPECT_LT((xDual.row(p.contacts.dofs[k]) - reference.row(p.contacts.dofs[k])).norm(), 1e-7);
  }
  // The K_cc-preconditioned dual needs several times fewer collision-free solves.
  EXPECT_LT(3 * solvesOf(dual), solvesOf(paper));
  EXPECT_LT(3 * solvesOf(dual), solvesOf(pcg));
}

TEST(PdContactSpeed, WarmStartFromTheLastForcesGivesTheSameSolution) {
  for (ContactSolveKind kind : {ContactSolveKind::DualThenPcg, ContactSolveKind::DualCgThenPcg}) {
    Problem p = makeProblem(0.05, 0.25);
    Eigen::MatrixX3d free;
    p.solver->solve(p.b, free);
    ContactWarmStart warm;
    Eigen::MatrixX3d x = free;
    solveWithContacts(p.system->matrix(), *p.solver, p.contacts, kind, 3000, 1e-8, x, 1, &warm, 3000);
    ASSERT_EQ(warm.force.rows(), free.rows());
    // Kept forces: w_k (p_k - x_k) at the solution (checked against the direct one), 0 off the contacts.
    {
      const Eigen::MatrixX3d first = direct(p);
      for (int k = 0; k < p.contacts.size(); ++k) {
        const Eigen::RowVector3d f = 1e6 * (p.contacts.targets.row(k) - first.row(p.contacts.dofs[k]));
        EXPECT_LT((warm.force.row(p.contacts.dofs[k]) - f).norm(), 1e-3 * (1.0 + f.norm()));
      }
      EXPECT_EQ(warm.force.row(0).norm(), 0.0);  // a corner, far from the patch
    }
    // The next L-G iteration: targets moved by 1 mm tangentially, the collision-free solve a little lower.
    p.contacts.targets.col(0).array() += 1e-3;
    Eigen::MatrixX3d free2 = free;
    free2.col(1).array() -= 2e-3;
    p.b = p.system->matrix() * free2;
    const Eigen::MatrixX3d reference = direct(p);
    // At a preview's loose tolerance (1e-2) the warm start saves SD + PCG solves; at 1e-6, and with the dual CG,
    // the few iterations it saves (log of the 6e-2 start residual) are about the one solve it costs (K^-1 S^T mu_0).
    const ContactWarmStart kept = warm;
    for (double tolerance : {1e-2, 1e-6}) {
      warm = kept;
      Eigen::MatrixX3d xCold = free2, xWarm = free2;
      const ContactSolveStats cold = solveWithContacts(p.system->matrix(), *p.solver, p.contacts, kind, 3000,
                                                       tolerance, xCold, 1, nullptr, 3000);
      const ContactSolveStats hot = solveWithContacts(p.system->matrix(), *p.solver, p.contacts, kind, 3000,
                                                      tolerance, xWarm, 1, &warm, 3000);
      std::printf("[ PdContactSpeed ] %s, tolerance %.0e: cold %d solves, warm %d solves (warm-start residual %.2e)\n",
                  kind == ContactSolveKind::DualThenPcg ? "SD + PCG" : "dual CG", tolerance, solvesOf(cold),
                  solvesOf(hot), hot.warmRelativeResidual);
      EXPECT_LT(hot.warmRelativeResidual, 0.2);
      // Never more than the warm start's own solve worse; the SD phase (one update) gains at a loose tolerance.
      EXPECT_LE(solvesOf(hot), solvesOf(cold) + 1);
      if (tolerance > 1e-3 && kind == ContactSolveKind::DualThenPcg) {
        EXPECT_LT(solvesOf(hot), solvesOf(cold));
      }
      const double scale = reference.norm();
      EXPECT_LT((xWarm - reference).norm(), (tolerance > 1e-3 ? 1e-2 : 1e-4) * scale);
      EXPECT_LT((xCold - reference).norm(), (tolerance > 1e-3 ? 1e-2 : 1e-4) * scale);
    }
  }
}

TEST(PdContactSpeed, StaleWarmStartIsDropped) {
  Problem p = makeProblem(0.05, 0.25);
  Eigen::MatrixX3d free;
  p.solver->solve(p.b, free);
  ContactWarmStart warm;
  warm.force = Eigen::MatrixX3d::Zero(free.rows(), 3);
  for (int d : p.contacts.dofs) warm.force(d, 1) = -50.0;  // pushes into the body: far worse than nothing
  const Eigen::MatrixX3d reference = direct(p);
  Eigen::MatrixX3d x = free;
  const ContactSolveStats st = solveWithContacts(p.system->matrix(), *p.solver, p.contacts,
                                                 ContactSolveKind::DualCgThenPcg, 3000, 1e-8, x, 1, &warm, 3000);
  EXPECT_GE(st.warmRelativeResidual, 1.0);
  EXPECT_LT((x - reference).norm(), 1e-5 * reference.norm());
}

// A vertex far from the body at the step start, not moving by inertia, that the global solve carries through the
// body (a stitch closing a seam across it): the broad phase must still watch it, and CCD must push it back.
TEST(PdContactSpeed, VertexCarriedThroughTheBodyByInternalForcesIsCaught) {
  auto collider = std::make_shared<collision::AvatarCollider>(makeIcosphere(Eigen::Vector3d::Zero(), 0.1, 3));
  AvatarContacts contacts(collider, AvatarContactOptions{0.004, 0.02, 1e6, 0.0, true});
  Eigen::MatrixX3d start(2, 3);
  start << 0.0, 0.0, 0.3,  // 20 cm in front of the sphere
      0.0, 0.5, 0.0;       // far above, stays
  contacts.beginStep(start, start, {0, 1});
  EXPECT_EQ(contacts.candidateCount(), 0);
  Eigen::MatrixX3d xFree = start;
  xFree.row(0) << 0.0, 0.0, -0.15;  // through the sphere to the back, 5 cm behind it
  ContactAccumulator acc(2);
  const AvatarContactStats st = contacts.addConstraints(xFree, acc);
  const ContactSet set = acc.merged();
  ASSERT_EQ(set.size(), 1);
  EXPECT_EQ(set.dofs[0], 0);
  EXPECT_EQ(st.ccdContacts, 1);
  // Target on the front side (the side it came from), at the thickness.
  EXPECT_GT(set.targets(0, 2), 0.0);
  EXPECT_NEAR(collider->signedDistance(set.targets.row(0).transpose()), 0.004, 1e-3);
}

// The broad phase looks only at DOFs that may be in contact (moved at least their start distance minus the
// thickness), yet every DOF within the thickness of the body at its collision-free position, or whose step
// crossed into it, gets its constraint. Reference: every DOF checked directly; the sphere mesh is convex, so the
// signed distance along a segment is convex and its minimum (did the step pass through the body?) is found by
// ternary search.
TEST(PdContactSpeed, WatchingOnlyDofsThatMayTouchKeepsEveryConstraint) {
  auto collider = std::make_shared<collision::AvatarCollider>(makeIcosphere(Eigen::Vector3d::Zero(), 0.1, 3));
  const double thickness = 0.004;
  AvatarContacts contacts(collider, AvatarContactOptions{thickness, 0.02, 1e6, 0.0, true});
  const int n = 3000;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), startGap(-0.002, 0.06), moveLength(0.0, 0.03);
  auto direction = [&] {
    Eigen::Vector3d d(unit(rng), unit(rng), unit(rng));
    while (d.norm() < 0.1) d = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    return Eigen::Vector3d(d.normalized());
  };
  Eigen::MatrixX3d start(n, 3), xFree(n, 3);
  std::vector<int> free(n);
  for (int d = 0; d < n; ++d) {
    free[d] = d;
    start.row(d) = ((0.1 + startGap(rng)) * direction()).transpose();
    xFree.row(d) = start.row(d) + moveLength(rng) * direction().transpose();
  }
  // Rounds: the first without hints; the second with the hints and the distance bounds the first one left (carried
  // over unchanged); the third and fourth after every start moved by up to 2 cm at its distance from the centre
  // (starts stay in the range above), so that the carried bounds shrink by the move and some DOFs are queried
  // again.
  std::uniform_real_distribution<double> startMove(0.0, 0.02);
  for (int round = 0; round < 4; ++round) {
    if (round >= 2)
      for (int d = 0; d < n; ++d) {
        const Eigen::RowVector3d step = xFree.row(d) - start.row(d);
        const double radius = start.row(d).norm();
        start.row(d) = radius * (start.row(d) + startMove(rng) * direction().transpose()).normalized();
        xFree.row(d) = start.row(d) + step;
      }
    contacts.beginStep(start, start, free);
    ContactAccumulator acc(n);
    const AvatarContactStats st = contacts.addConstraints(xFree, acc);
    const ContactSet set = acc.merged();
    std::vector<char> constrained(n, 0);
    for (int k = 0; k < set.size(); ++k) constrained[set.dofs[k]] = 1;
    int expected = 0, candidates = contacts.candidateCount();
    for (int d = 0; d < n; ++d) {
      const Eigen::Vector3d a = start.row(d).transpose(), b = xFree.row(d).transpose();
      auto along = [&](double t) { return collider->signedDistance(a + t * (b - a)); };
      double lo = 0.0, hi = 1.0;
      for (int it = 0; it < 100; ++it) {
        const double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
        if (along(m1) < along(m2)) hi = m2;
        else lo = m1;
      }
      const double deepest = std::min({along(0.0), along(0.5 * (lo + hi)), along(1.0)});
      const bool crossed = along(0.0) > 0.0 && deepest < 0.0;
      const bool want = crossed || along(1.0) < thickness;
      expected += want;
      EXPECT_EQ(constrained[d] != 0, want) << "DOF " << d << " start gap " << along(0.0) << " end gap " << along(1.0)
                                           << " deepest " << deepest;
    }
    EXPECT_EQ(set.size(), expected);
    EXPECT_GT(expected, n / 10);
    // Fewer queries than the candidates alone (the old rule looked at every candidate, and more).
    EXPECT_LT(st.watched, candidates);
    EXPECT_GE(st.watched, expected);
  }
}

TEST(PdContactSpeed, ChurnCountsDofsJoiningAndLeaving) {
  ContactSet current;
  current.dofs = {3, 5, 9, 12};
  std::vector<char> scratch;
  EXPECT_EQ(contactChurn({5, 3, 12, 9}, current, scratch), 0);
  EXPECT_EQ(contactChurn({1, 3, 5}, current, scratch), 3);  // 1 left; 9 and 12 joined
  EXPECT_EQ(contactChurn({}, current, scratch), 4);
  for (char c : scratch) EXPECT_EQ(c, 0);
}

// A tablecloth dropped on a sphere with each contact solve: no vertex deeper than the thickness, and the
// K_cc-preconditioned dual with a warm start needs fewer PCG + dual solves than the paper's solve.
TEST(PdContactSpeed, ClothOnSphereSettlesWithDualCgAndWarmStart) {
  GridClothOptions o;
  o.nx = o.ny = 25;
  o.horizontal = true;
  o.elevation = 0.33;
  o.pinTopCorners = false;
  const drape::model::ClothModel model = makeGridCloth(o);
  auto collider = std::make_shared<collision::AvatarCollider>(makeIcosphere(Eigen::Vector3d::Zero(), 0.3, 4));
  int solves[2] = {0, 0};
  int index = 0;
  for (bool fast : {false, true}) {
    PreviewSettings s;
    s.domains = 4;
    s.contactSolve = fast ? ContactSolveKind::DualCgThenPcg : ContactSolveKind::DualThenPcg;
    s.contactWarmStart = fast;
    PreviewSolver solver(model, s, collider);
    for (int i = 0; i < 40; ++i) {
      const PreviewReport r = solver.step();
      ASSERT_NE(r.status, PreviewStatus::Diverged);
      solves[index] += r.sdIterations + r.pcgIterations;
    }
    const Eigen::VectorXd& x = solver.positions();
    double minDistance = 1e9;
    for (int v = 0; v < model.numVertices(); ++v)
      minDistance = std::min(minDistance, collider->signedDistance(x.segment<3>(3 * v)));
    EXPECT_GT(minDistance, -s.contactThickness);
    const int centre = 12 * 25 + 12;
    EXPECT_NEAR(x[3 * centre + 1], 0.3 + s.contactThickness, 0.01);
    ++index;
  }
  std::printf("[ PdContactSpeed ] cloth on sphere, 40 steps: paper %d solves, dual CG + warm start %d\n", solves[0],
              solves[1]);
  EXPECT_LT(solves[1], solves[0]);
}

}  // namespace
}  // namespace drape::pd
