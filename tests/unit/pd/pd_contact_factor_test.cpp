// ContactFactor (contact_factor.h): the collision-aware global solve by a Cholesky factor of K + Delta K, checked
// against an independent sparse LDL^T of the same system (pd_contact_problem.h) after refactorisations and after
// rank-k updates/downdates of the factor when a few contact DOFs change.
#include <gtest/gtest.h>

#include "drape/pd/contact_factor.h"
#include "pd_contact_problem.h"

namespace drape::pd {
namespace {

TEST(PdContactFactor, SolvesEquationFourteenLikeADirectSolve) {
  test::ContactProblem p = test::makeContactProblem(41, 0.05, 0.25);
  ASSERT_GT(p.contacts.size(), 200);
  ContactFactor factor(p.system->matrix());
  const auto freeSolve = [&] {
    Eigen::MatrixX3d x;
    p.solver->solve(p.b, x);
    return x;
  };
  const auto expectDirect = [&](const Eigen::MatrixX3d& x) {
    const Eigen::MatrixX3d reference = test::directContactSolution(p);
    EXPECT_LT((x - reference).norm(), 1e-9 * reference.norm());
  };

  Eigen::MatrixX3d x = freeSolve();
  ASSERT_TRUE(factor.solve(p.contacts, x));
  expectDirect(x);
  EXPECT_EQ(factor.factorisations(), 1);

  // The right-hand side given (as the preview passes it) instead of formed again as K x: the same solution.
  Eigen::MatrixX3d withB = freeSolve();
  ASSERT_TRUE(factor.solve(p.contacts, withB, &p.b));
  expectDirect(withB);
  EXPECT_LT((withB - x).norm(), 1e-12 * x.norm());

  // New targets on the same DOFs and weights: the same factor.
  p.contacts.targets.col(1).array() += 0.01;
  x = freeSolve();
  ASSERT_TRUE(factor.solve(p.contacts, x));
  expectDirect(x);
  EXPECT_EQ(factor.factorisations(), 1);

  // A few DOFs leave and a few join, one changes its weight: an update/downdate of the factor.
  const ContactSet all = p.contacts;
  const auto subset = [&](int stride, int offset) {
    ContactSet out;
    for (int k = offset; k < all.size(); k += stride) {
      out.dofs.push_back(all.dofs[k]);
      out.weights.push_back(all.weights[k]);
    }
    out.targets.resize(out.size(), 3);
    for (int k = 0; k < out.size(); ++k) out.targets.row(k) = all.targets.row(offset + stride * k);
    return out;
  };
  p.contacts = subset(1, 5);  // 5 leave
  p.contacts.dofs.push_back(0);  // a corner joins (not in the patch)
  p.contacts.weights.push_back(3e5);
  p.contacts.targets.conservativeResize(p.contacts.size(), 3);
  p.contacts.targets.row(p.contacts.size() - 1) << 0.0, -0.2, 0.0;
  p.contacts.weights[0] *= 2.0;
  x = freeSolve();
  ASSERT_TRUE(factor.solve(p.contacts, x));
  expectDirect(x);
  EXPECT_EQ(factor.factorisations(), 1);
  EXPECT_EQ(factor.updates(), 1);

  // Many updates in a row keep the accuracy (each is checked against a fresh direct solve).
  for (int round = 0; round < 10; ++round) {
    p.contacts = subset(1, round % 2 == 0 ? 3 : 7);
    x = freeSolve();
    ASSERT_TRUE(factor.solve(p.contacts, x));
    expectDirect(x);
  }
  EXPECT_EQ(factor.factorisations(), 1);
  EXPECT_EQ(factor.updates(), 11);

  // More than maxUpdates DOFs change: refactorised, with K's own diagonal back on the DOFs that left.
  p.contacts = subset(2, 0);
  ASSERT_GT(all.size() - p.contacts.size(), ContactFactor::maxUpdates(static_cast<int>(p.system->matrix().rows())));
  x = freeSolve();
  ASSERT_TRUE(factor.solve(p.contacts, x));
  expectDirect(x);
  EXPECT_EQ(factor.factorisations(), 2);

  // No contacts: the collision-free solution, K^-1 b.
  const Eigen::MatrixX3d free = freeSolve();
  x = free;
  ASSERT_TRUE(factor.solve(ContactSet{}, x));
  EXPECT_LT((x - free).norm(), 1e-9 * free.norm());
}

}  // namespace
}  // namespace drape::pd
