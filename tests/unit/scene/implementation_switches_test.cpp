// Scene::implementation (scene/implementation.h) reaches the solvers, and its switches give the same drape: the
// preview's monolithic CHOLMOD global solve against the domains (pd-dd: equal to round-off), and the Newton drape
// with every speed-up implementation off against all on (equal to the solver's tolerances).
#include <gtest/gtest.h>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

Scene coarseDefaultScene(const char* stage) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "default.json";
  request.overrides = {{"solver.stage", stage}, {"mesh.target_edge_length", "0.04"}};
  return loadScene(request);
}

Eigen::MatrixX3d positionsAfter(Scene scene, int steps) {
  Simulation sim(std::move(scene));
  for (int i = 0; i < steps && !sim.finished(); ++i) EXPECT_NE(sim.step().status, StepStatus::Diverged);
  return sim.positions();
}

TEST(ImplementationSwitches, MonolithicPreviewSolveGivesTheDomainDecomposedPreview) {
  Scene domains = coarseDefaultScene("preview");
  Scene monolithic = domains;
  monolithic.implementation.monolithicGlobalSolve = true;
  const Eigen::MatrixX3d a = positionsAfter(domains, 20);
  const Eigen::MatrixX3d b = positionsAfter(monolithic, 20);
  const Eigen::MatrixX3d placed = Simulation(coarseDefaultScene("preview")).positions();
  ASSERT_GT((a - placed).rowwise().norm().maxCoeff(), 1e-3) << "the preview moved the garment";
  EXPECT_LT((a - b).rowwise().norm().maxCoeff(), 1e-6);
}

TEST(ImplementationSwitches, DrapeWithEverySpeedUpOffMatchesTheDefault) {
  // 40 steps at the paper's 1 ms step limit, none split: at longer steps a round-off difference can flip a step's
  // split, and the two runs then take different steps.
  Scene fast = coarseDefaultScene("drape");
  fast.settings.set("solver.newton.h_max", "1e-3", "test");
  Scene plain = fast;
  plain.implementation.closedFormBending = false;
  plain.implementation.blockMap = false;
  plain.implementation.parallelAssembly = false;
  plain.implementation.foldDissipation = false;
  plain.implementation.batchedGradients = false;
  plain.implementation.reorderDofs = false;
  plain.implementation.fusedKernels = false;
  const Eigen::MatrixX3d a = positionsAfter(fast, 40);
  const Eigen::MatrixX3d b = positionsAfter(plain, 40);
  const Eigen::MatrixX3d placed = Simulation(fast).positions();
  const double moved = (a - placed).rowwise().norm().maxCoeff();
  ASSERT_GT(moved, 1e-4) << "the drape moved the garment";
  // PCG stops at a relative tolerance, so the two solves differ within it, far below the motion itself.
  EXPECT_LT((a - b).rowwise().norm().maxCoeff(), 1e-2 * moved);
}

}  // namespace
}  // namespace drape::test
