// Anderson acceleration of the preview's L-G loop (anderson.h): on a slow linear fixed point against the exact
// solution, and on the hanging cloth against the plain loop's converged steps.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>

#include "drape/pd/anderson.h"
#include "drape/pd/grid_cloth.h"
#include "drape/pd/preview_solver.h"

namespace drape::pd {
namespace {

// x <- A x + c with A symmetric, eigenvalues in [0, 0.99]: plain iteration needs ~2,000 iterations for 1e-9.
struct LinearMap {
  Eigen::MatrixXd a;
  Eigen::MatrixX3d c;
  Eigen::MatrixX3d apply(const Eigen::MatrixX3d& x) const { return a * x + c; }
};

LinearMap slowLinearMap(int n) {
  const Eigen::MatrixXd q = Eigen::MatrixXd::Random(n, n).householderQr().householderQ();
  Eigen::VectorXd eigenvalues = Eigen::VectorXd::LinSpaced(n, 0.0, 0.99);
  return {q * eigenvalues.asDiagonal() * q.transpose(), Eigen::MatrixX3d::Random(n, 3)};
}

int iterationsTo(const LinearMap& map, const Eigen::MatrixX3d& exact, AndersonMixer* mixer, Eigen::MatrixX3d& x) {
  x = Eigen::MatrixX3d::Zero(exact.rows(), 3);
  for (int it = 1; it <= 20000; ++it) {
    const Eigen::MatrixX3d g = map.apply(x);
    x = mixer ? mixer->next(x, g) : g;
    if ((x - exact).norm() < 1e-9 * exact.norm()) return it;
  }
  return -1;
}

TEST(AndersonMixer, SolvesASlowLinearFixedPointExactlyInFarFewerIterations) {
  std::srand(7);
  const LinearMap map = slowLinearMap(40);
  const Eigen::MatrixX3d exact =
      (Eigen::MatrixXd::Identity(40, 40) - map.a).partialPivLu().solve(Eigen::MatrixXd(map.c));
  Eigen::MatrixX3d plainX, andersonX;
  const int plain = iterationsTo(map, exact, nullptr, plainX);
  AndersonMixer mixer(5);
  const int anderson = iterationsTo(map, exact, &mixer, andersonX);
  std::printf("[ AndersonMixer ] iterations to 1e-9: plain %d, Anderson(5) %d\n", plain, anderson);
  ASSERT_GT(plain, 0);
  ASSERT_GT(anderson, 0);
  EXPECT_LT(5 * anderson, plain);
  EXPECT_LT((andersonX - exact).norm(), 1e-9 * exact.norm());
}

TEST(AndersonMixer, ARisingResidualRestartsFromThePlainStep) {
  AndersonMixer mixer(3);
  const Eigen::MatrixX3d x = Eigen::MatrixX3d::Zero(4, 3);
  const Eigen::MatrixX3d g1 = Eigen::MatrixX3d::Constant(4, 3, 1.0);
  EXPECT_TRUE(mixer.next(x, g1).isApprox(g1));  // no history: the plain step
  const Eigen::MatrixX3d g2 = Eigen::MatrixX3d::Constant(4, 3, 5.0);  // residual 4 > 1: grew
  EXPECT_TRUE(mixer.next(g1, g2).isApprox(g2));
  EXPECT_EQ(mixer.restarts(), 1);
}

// After a restart the extrapolation uses only what came after it: a mixer with a history before the restart gives
// the same iterates as a fresh one fed the same points from the restart on.
TEST(AndersonMixer, ARestartForgetsTheWholeHistory) {
  std::srand(11);
  const LinearMap map = slowLinearMap(12);
  AndersonMixer used(4), fresh(4);
  Eigen::MatrixX3d x = Eigen::MatrixX3d::Zero(12, 3);
  for (int it = 0; it < 3; ++it) x = used.next(x, map.apply(x));  // two differences stored
  // A point whose move is far larger than the last one: the used mixer restarts, the fresh one starts.
  const Eigen::MatrixX3d far = x + Eigen::MatrixX3d::Constant(12, 3, 10.0);
  Eigen::MatrixX3d a = used.next(far, map.apply(far)), b = fresh.next(far, map.apply(far));
  ASSERT_EQ(used.restarts(), 1);
  for (int it = 0; it < 6; ++it) {
    EXPECT_LT((a - b).norm(), 1e-12 * b.norm()) << "iteration " << it;
    const Eigen::MatrixX3d ga = map.apply(a), gb = map.apply(b);
    a = used.next(a, ga);
    b = fresh.next(b, gb);
  }
}

// The accelerated loop reaches the plain loop's converged step in fewer L-G iterations, for both local steps and
// both shear models (no contact: the fixed-point map is smooth).
TEST(PdPreviewAnderson, HangingClothReachesThePlainLoopsStatesInFewerIterations) {
  GridClothOptions o;
  o.nx = o.ny = 30;
  const drape::model::ClothModel model = makeGridCloth(o);
  for (ShearModelKind shear : {ShearModelKind::Stretch, ShearModelKind::Fabric})
    for (LocalStepKind local : {LocalStepKind::GaussSeidel, LocalStepKind::Jacobi}) {
      PreviewSettings s;
      s.domains = 4;
      s.maxIterations = 2000;
      s.maxHalvings = 0;
      s.tolerance = 1e-7;
      s.shearModel = shear;
      s.localStep = local;
      const auto run = [&](int window, Eigen::VectorXd& x) {
        s.andersonWindow = window;
        PreviewSolver solver(model, s);
        int total = 0;
        for (int i = 0; i < 10; ++i) {
          const PreviewReport r = solver.step();
          EXPECT_EQ(r.status, PreviewStatus::Converged);
          total += r.iterations;
        }
        x = solver.positions();
        return total;
      };
      Eigen::VectorXd plainX, andersonX;
      const int plain = run(0, plainX);
      const int anderson = run(5, andersonX);
      std::printf("[ PdPreviewAnderson ] %s shear, %s: L-G iterations over 10 steps: plain %d, Anderson(5) %d\n",
                  shear == ShearModelKind::Stretch ? "stretch-held" : "fabric",
                  local == LocalStepKind::Jacobi ? "Jacobi" : "Gauss-Seidel", plain, anderson);
      EXPECT_LT(anderson, plain);
      EXPECT_LT((andersonX - plainX).cwiseAbs().maxCoeff(), 1e-4);
    }
}

}  // namespace
}  // namespace drape::pd
