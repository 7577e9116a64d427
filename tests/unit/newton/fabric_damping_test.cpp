// The fabric's damping is the drape's stretch dissipation beta_s (assets/fabrics/README.md): a fabric without it has
// no stretch_damping term, and its value changes how the cloth falls. With panels of several fabrics the scene takes
// the largest, as it does for friction.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

struct Fall {
  std::vector<std::string> terms;
  Eigen::MatrixX3d positions;
};

Fall dropTablecloth(const std::string& damping) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "tablecloth.json";
  request.overrides = {{"mesh.target_edge_length", "0.1"},
                       {"solver.stage", "drape"},
                       {"solver.newton.relaxation", "false"},
                       {"solver.max_sim_time", "0.5"}};
  if (!damping.empty()) request.overrides.emplace_back("fabric.damping", damping);
  Simulation sim(loadScene(request));
  while (!sim.finished()) sim.step();
  return {sim.terms(), sim.positions()};
}

bool has(const std::vector<std::string>& terms, const std::string& name) {
  return std::find(terms.begin(), terms.end(), name) != terms.end();
}

TEST(FabricDamping, IsTheDrapesStretchDissipation) {
  const Fall none = dropTablecloth("0");
  const Fall preset = dropTablecloth("");
  const Fall heavy = dropTablecloth("1");
  EXPECT_FALSE(has(none.terms, "stretch_damping"));
  EXPECT_TRUE(has(preset.terms, "stretch_damping"));
  EXPECT_TRUE(has(heavy.terms, "stretch_damping"));
  // A second of stretch dissipation against the preset's hundredth holds the falling cloth's stretching back.
  const double moved = (heavy.positions - preset.positions).rowwise().norm().maxCoeff();
  EXPECT_GT(moved, 1e-3) << "the fabric's damping changed nothing";
}

}  // namespace
}  // namespace drape::test
