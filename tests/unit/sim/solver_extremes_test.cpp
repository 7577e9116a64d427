// Both solvers at the extremes of the settings a user can give (the settings' own ranges): very stiff and very soft
// fabric, heavy and light cloth, stiff bending, high friction, tiny and huge time steps, coarse and fine meshes.
// The tablecloth falls onto the sphere (assets/scenes/tablecloth.json, coarsened); every run must stay finite, never
// diverge, and keep every vertex out of the sphere beyond the contact thickness. The preview at a 0.1 s step with a
// 1e7 N/m fabric converged with a vertex 51 mm inside the sphere before its contacts were weighted above the
// fabric (pd::contactWeightFor).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "drape/collision/avatar_collider.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "drape/sim/snapshot_builder.h"
#include "shared_data.h"

namespace drape::test {
namespace {

struct Extreme {
  const char* name;
  double simTime;  // seconds simulated per solver
  std::vector<std::pair<std::string, std::string>> settings;
};

void PrintTo(const Extreme& e, std::ostream* os) { *os << e.name; }

class SolverExtremes : public ::testing::TestWithParam<Extreme> {};

TEST_P(SolverExtremes, StayFiniteAndOutOfTheSphere) {
  const Extreme& e = GetParam();
  for (const char* stage : {"drape", "preview"}) {
    SCOPED_TRACE(stage);
    SceneRequest request;
    request.input = assetsDir() / "scenes" / "tablecloth.json";
    request.overrides = {{"mesh.target_edge_length", "0.05"},
                         {"solver.stage", stage},
                         {"solver.max_sim_time", std::to_string(e.simTime)}};
    for (const auto& s : e.settings) request.overrides.push_back(s);
    Simulation sim(loadScene(request));
    const collision::AvatarCollider sphere(mergedColliders(sim.scene()));
    int steps = 0, unconverged = 0;
    double worstStrain = 0.0;
    while (!sim.finished()) {
      const StepReport r = sim.step();
      ASSERT_NE(r.status, StepStatus::Diverged) << "t = " << r.time;
      ASSERT_TRUE(std::isfinite(r.maxStrain)) << "t = " << r.time;
      worstStrain = std::max(worstStrain, r.maxStrain);
      unconverged += r.status == StepStatus::MaxIterations;
      ++steps;
    }
    const Eigen::MatrixX3d x = sim.positions();
    ASSERT_TRUE(x.allFinite());
    double deepest = 0.0;
    for (int v = 0; v < x.rows(); ++v) deepest = std::min(deepest, sphere.signedDistance(x.row(v).transpose()));
    std::printf("[ SolverExtremes ] %-16s %-7s %5d steps (%d at the iteration cap), largest stretch %.3g, deepest "
                "%.2f mm\n", e.name, stage, steps, unconverged, worstStrain, 1e3 * -deepest);
    EXPECT_GT(deepest, -sim.contactThickness()) << "a vertex is inside the sphere beyond the contact thickness";
  }
}

const std::vector<Extreme> kExtremes = {
    {"stiff", 0.6, {{"fabric.stretch_warp", "1e7"}, {"fabric.stretch_weft", "1e7"}, {"fabric.shear", "1e7"}}},
    {"softest_stretch", 0.6, {{"fabric.stretch_warp", "1e-3"}, {"fabric.stretch_weft", "1e-3"}, {"fabric.shear", "0"}}},
    {"stiff_bending", 0.6, {{"fabric.bend_warp", "1"}, {"fabric.bend_weft", "1"}}},
    {"heavy", 0.6, {{"fabric.density", "10"}}},
    {"light", 0.6, {{"fabric.density", "1e-4"}}},
    {"friction", 0.6, {{"fabric.friction", "5"}}},
    {"huge_steps", 0.6, {{"solver.newton.h_max", "0.1"}, {"solver.preview.time_step", "0.1"}}},
    {"stiff_huge_steps", 0.6,
     {{"fabric.stretch_warp", "1e7"},
      {"fabric.stretch_weft", "1e7"},
      {"fabric.shear", "1e7"},
      {"solver.newton.h_max", "0.1"},
      {"solver.preview.time_step", "0.1"}}},
    {"heavy_soft_huge_steps", 0.6,
     {{"fabric.density", "10"},
      {"fabric.stretch_warp", "1"},
      {"fabric.stretch_weft", "1"},
      {"fabric.shear", "1"},
      {"solver.newton.h_max", "0.1"},
      {"solver.preview.time_step", "0.1"}}},
    {"tiny_steps", 0.003, {{"solver.newton.h_max", "1e-5"}, {"solver.preview.time_step", "1e-5"}}},
    {"coarse_mesh", 0.6, {{"mesh.target_edge_length", "0.3"}}},
    {"fine_mesh", 0.03, {{"mesh.target_edge_length", "0.015"}}},
};

INSTANTIATE_TEST_SUITE_P(Settings, SolverExtremes, ::testing::ValuesIn(kExtremes),
                         [](const ::testing::TestParamInfo<Extreme>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace drape::test
