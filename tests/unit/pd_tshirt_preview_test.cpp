// Issue 6: the preview of the t-shirt on the default mannequin settles without NaN and without vertices inside the
// body, and the full pipeline ends in the Newton drape. DISABLED: the preview does not yet do this (measured at stop
// 11, default scene, 2 cm mesh, stretch-held shear): its largest triangle stretch grows from 2.4 after the first
// step (the seams close in one step) to 24 at t = 1 s under the L-G cap of 30, and the shirt then falls through the
// body (at 1.5 s every vertex is between y = 0.26 and 0.42 m, against 0.85-1.44 m in the Newton drape; contacts
// 2,600 -> 1). At the 1 cm mesh (bench/scenes/tshirt_female.json) the preview ends at 4,800 % strain and the Newton
// drape from it diverges. With solver.preview.relaxation_time = 0.1 s the stretch still reaches 15 and the shirt
// still slides (lowest vertex 0.40 m); with solver.preview.time_step = 1/500 s the L-G loop converges and the shirt
// stays on (docs/BENCHMARKS.md, end to end). Run with --gtest_also_run_disabled_tests it fails on the stretch (24.6; the
// pipeline hands over at 1 s, before the fall). Runs ~50-80 s; enable it when the preview keeps the garment on the
// body.
#include <gtest/gtest.h>

#include "drape/collision/avatar_collider.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "drape/sim/snapshot_builder.h"
#include "shared_data.h"

namespace drape::test {

TEST(PdTshirtPreview, DISABLED_DefaultSceneStaysOnTheBodyAndHandsOverToTheDrape) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "default.json";
  request.overrides = {{"solver.stage", "full"}};
  Simulation sim(loadScene(request));
  const collision::AvatarCollider body(mergedColliders(sim.scene()));
  double worstStrain = 0.0;
  while (!sim.finished() && sim.stage() == "preview") {
    const StepReport r = sim.step();
    ASSERT_NE(r.status, StepStatus::Diverged) << "t = " << r.time;
    worstStrain = std::max(worstStrain, r.maxStrain);
  }
  EXPECT_LT(worstStrain, 0.5);
  const Eigen::MatrixX3d x = sim.positions();
  ASSERT_TRUE(x.allFinite());
  int inside = 0, away = 0;
  for (int v = 0; v < x.rows(); ++v) {
    const double d = body.signedDistance(x.row(v).transpose());
    inside += d < -sim.contactThickness();
    away += d > 0.1;  // a worn t-shirt hangs at most a few centimetres off the body
  }
  EXPECT_EQ(inside, 0);
  EXPECT_EQ(away, 0);
  // The full pipeline continues in the Newton drape and does not diverge there.
  for (int i = 0; i < 200 && !sim.finished(); ++i) ASSERT_NE(sim.step().status, StepStatus::Diverged);
  EXPECT_EQ(sim.stage(), "drape");
}

}  // namespace drape::test
