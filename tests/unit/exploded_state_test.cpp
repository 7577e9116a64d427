// An exploded garment ends the run Diverged in every stage, with the state before the step that exploded kept and
// the triangle that tore named; a free fall, however far, is not an explosion. The exploding scene is the default
// t-shirt with the softest stretch stiffness the settings admit, no shear or bending stiffness, 1000 m/s^2 gravity
// and 0.1 s steps: no fabric holds it together.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "drape/geometry/strain.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

std::vector<std::pair<std::string, std::string>> nothingHoldsIt() {
  return {{"fabric.stretch_warp", "1e-3"}, {"fabric.stretch_weft", "1e-3"}, {"fabric.shear", "0"},
          {"fabric.bend_warp", "0"},       {"fabric.bend_weft", "0"},       {"sim.gravity", "-1000"},
          {"solver.newton.h_max", "0.1"},  {"solver.max_sim_time", "0.5"}};
}

Scene sceneWith(const std::string& file, std::vector<std::pair<std::string, std::string>> overrides) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / file;
  request.overrides = std::move(overrides);
  return loadScene(request);
}

struct Stage {
  const char* name;
  std::vector<std::pair<std::string, std::string>> settings;
};

TEST(ExplodedState, EndsDivergedInEveryStageWithTheStateBeforeIt) {
  const std::vector<Stage> stages = {
      {"drape", {{"solver.stage", "drape"}}},
      {"projective preview", {{"solver.stage", "preview"}}},
      {"quasi-Newton preview", {{"solver.stage", "preview"}, {"solver.preview.method", "quasi_newton"}}},
      {"pipeline", {{"solver.stage", "full"}}}};
  for (const Stage& stage : stages) {
    SCOPED_TRACE(stage.name);
    auto overrides = nothingHoldsIt();
    overrides.insert(overrides.end(), stage.settings.begin(), stage.settings.end());
    Simulation sim(sceneWith("default.json", overrides));
    Eigen::MatrixX3d before = sim.positions();
    StepReport last;
    while (!sim.finished()) {
      before = sim.positions();
      last = sim.step();
      if (last.status == StepStatus::Diverged) break;
    }
    ASSERT_EQ(last.status, StepStatus::Diverged) << "ended " << sim.endReason() << " at t = " << sim.time();
    const std::string& why = sim.divergedReason();
    EXPECT_NE(why.find("exploded"), std::string::npos) << why;
    EXPECT_NE(why.find(" of panel '"), std::string::npos) << why;
    // The state kept is the one before the step, and the garment in it is not exploded.
    EXPECT_TRUE(sim.positions().isApprox(before, 0.0)) << why;
    const Eigen::VectorXd stretch = triangleStretch(sim.garment().rest, sim.positions(), sim.garment().triangles);
    EXPECT_LE(stretch.maxCoeff(), 100.0);
    EXPECT_GT(last.maxStrain, 100.0);
    // Nothing steps on from there.
    const int steps = sim.steps();
    EXPECT_EQ(sim.step().status, StepStatus::Diverged);
    EXPECT_EQ(sim.steps(), steps);
    EXPECT_TRUE(sim.positions().isApprox(before, 0.0));
  }
}

TEST(ExplodedState, AFreeFallIsNotAnExplosion) {
  // The soft tablecloth slides off the sphere and falls tens of metres at 1000 m/s^2 in 0.5 s, far outside the
  // scene's 2 m box but within the distance gravity carries it: the run ends at its time limit.
  auto overrides = nothingHoldsIt();
  overrides.emplace_back("solver.stage", "drape");
  Simulation sim(sceneWith("tablecloth.json", overrides));
  double lowest = 0.0;
  while (!sim.finished()) {
    const StepReport r = sim.step();
    ASSERT_NE(r.status, StepStatus::Diverged) << sim.divergedReason();
  }
  for (int v = 0; v < sim.positions().rows(); ++v) lowest = std::min(lowest, sim.positions()(v, 1));
  EXPECT_LT(lowest, -20.0);
  EXPECT_EQ(sim.endReason(), "MaxSimTime");
  EXPECT_TRUE(sim.divergedReason().empty());
}

}  // namespace
}  // namespace drape::test
