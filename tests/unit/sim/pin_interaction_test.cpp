// Moving pins, the grabbed-vertex spring and resuming an edited scene: in both solvers and through Simulation.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "drape/newton/newton_solver.h"
#include "drape/pd/grid_cloth.h"
#include "drape/pattern/pattern_edit.h"
#include "drape/pd/preview_solver.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "shared_data.h"

namespace drape::test {
namespace {

// A 0.5 m x 0.5 m cloth (11 x 11 vertices) hanging from its top corners.
drape::model::ClothModel smallCloth() {
  pd::GridClothOptions o;
  o.nx = o.ny = 11;
  o.width = o.height = 0.5;
  return pd::makeGridCloth(o);
}

Eigen::Vector3d vertex(const Eigen::VectorXd& x, int v) { return x.segment<3>(3 * v); }

// Both corners move up by 0.3 m and the right one also 0.2 m along +z, linearly over [0.05, 0.25] s.
Eigen::Vector3d cornerPath(const drape::model::ClothModel& model, int k, double t) {
  const double s = std::clamp((t - 0.05) / 0.2, 0.0, 1.0);
  const Eigen::Vector3d start = vertex(model.positions, model.pinned[k]);
  return start + s * Eigen::Vector3d(0.0, 0.3, k == 1 ? 0.2 : 0.0);
}

drape::model::ClothModel movingCornerCloth() {
  drape::model::ClothModel model = smallCloth();
  const drape::model::ClothModel initial = model;
  model.pinTrajectory = [initial](int k, double t) { return cornerPath(initial, k, t); };
  return model;
}

TEST(MovingPins, NewtonPinsFollowTheirTrajectory) {
  const drape::model::ClothModel model = movingCornerCloth();
  newton::NewtonSettings settings;
  settings.hMax = 2e-3;
  newton::NewtonSolver solver(model, settings);
  while (solver.time() < 0.3) ASSERT_NE(solver.step().status, newton::NewtonStatus::Diverged);
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d expected = cornerPath(model, k, solver.time());
    // Pins are 1e4 N/m springs carrying a 30 g cloth: they lag by well under a millimetre.
    EXPECT_LT((vertex(solver.positions(), model.pinned[k]) - expected).norm(), 1e-3) << "pin " << k;
  }
}

TEST(MovingPins, PreviewPinsFollowTheirTrajectoryExactly) {
  const drape::model::ClothModel model = movingCornerCloth();
  pd::PreviewSettings settings;
  settings.domains = 2;
  pd::PreviewSolver solver(model, settings);
  double lowest = 1.0;
  while (solver.time() < 0.3) {
    ASSERT_NE(solver.step().status, pd::PreviewStatus::Diverged);
    lowest = std::min(lowest, solver.positions()(3 * 60 + 1));  // centre vertex height
  }
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d expected = cornerPath(model, k, solver.time());
    EXPECT_LT((vertex(solver.positions(), model.pinned[k]) - expected).norm(), 1e-9) << "pin " << k;
  }
  // The cloth was carried up with its corners: its centre ends above where it started falling from.
  EXPECT_GT(solver.positions()(3 * 60 + 1), lowest + 0.1);
}

// The bottom-middle vertex of smallCloth, and a target 0.25 m in front of it.
constexpr int kGrabbed = 5;
const Eigen::Vector3d kPull(0.0, 0.0, 0.25);

template <class Solver>
double draggedDistance(Solver& solver, bool drag, int steps) {
  const Eigen::Vector3d target = vertex(solver.positions(), kGrabbed) + kPull;
  if (drag) solver.setDrag(kGrabbed, target);
  for (int i = 0; i < steps; ++i) solver.step();
  return (vertex(solver.positions(), kGrabbed) - target).norm();
}

TEST(Drag, PreviewVertexFollowsTheCursorSpring) {
  pd::PreviewSettings settings;
  settings.domains = 2;
  pd::PreviewSolver free(smallCloth(), settings), dragged(smallCloth(), settings);
  const double without = draggedDistance(free, false, 60);
  const Eigen::Vector3d target = vertex(dragged.positions(), kGrabbed) + kPull;
  const double with = draggedDistance(dragged, true, 60);
  EXPECT_GT(without, 0.2);  // nothing pulls it forwards: it hangs in the plane
  EXPECT_LT(with, 0.5 * without) << "without drag " << without;
  // Released, the spring no longer acts: the vertex swings away from the target (gravity pulls the cloth back
  // towards hanging in its plane).
  dragged.setDrag(-1, Eigen::Vector3d::Zero());
  double farthest = 0.0;
  for (int i = 0; i < 60; ++i) {
    dragged.step();
    farthest = std::max(farthest, (vertex(dragged.positions(), kGrabbed) - target).norm());
  }
  EXPECT_GT(farthest, with + 0.05);
}

TEST(Drag, NewtonVertexFollowsTheCursorSpring) {
  newton::NewtonSettings settings;
  settings.hMax = 4e-3;
  settings.relaxation = false;
  newton::NewtonSolver free(smallCloth(), settings), dragged(smallCloth(), settings);
  const double without = draggedDistance(free, false, 150);
  const double with = draggedDistance(dragged, true, 150);
  EXPECT_GT(without, 0.2);
  EXPECT_LT(with, 0.5 * without) << "without drag " << without;
  EXPECT_NE(std::find(dragged.energyNames().begin(), dragged.energyNames().end(), "drag"), dragged.energyNames().end());
}

Scene tablecloth(const std::string& stage, const std::string& fabric = "cotton_shirting") {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "tablecloth.json";
  request.overrides = {{"mesh.target_edge_length", "0.08"}, {"solver.stage", stage}, {"fabric.preset", fabric}};
  return loadScene(request);
}

TEST(Resume, EditedPreviewContinuesFromTheCurrentState) {
  Simulation first(tablecloth("preview"));
  for (int i = 0; i < 10; ++i) first.step();
  const ResumeState state = first.resumeState();
  EXPECT_EQ(state.stage, Stage::Preview);
  Simulation edited(tablecloth("preview", "denim"), state);
  EXPECT_TRUE(edited.resumed());
  EXPECT_EQ(edited.stage(), Stage::Preview);
  EXPECT_DOUBLE_EQ(edited.time(), first.time());
  EXPECT_LT((edited.positions() - first.positions()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NE(edited.snapshot().stage, Stage::Placed);
  // It keeps moving with the velocities it had, not from rest: the next steps match the unedited run's
  // direction of travel (both fall).
  const double before = edited.positions().col(1).mean();
  edited.step();
  EXPECT_LT(edited.positions().col(1).mean(), before);
}

TEST(Resume, EditedDrapeRestartsFromTheLastPreviewState) {
  Scene scene = tablecloth("full");
  scene.settings.set("solver.preview.max_time", "0.1", "test");
  Simulation first(std::move(scene));
  while (first.stage() == Stage::Preview) first.step();
  const Eigen::MatrixX3d previewEnd = first.positions();
  const double previewEndTime = first.time();
  for (int i = 0; i < 60; ++i) first.step();
  ASSERT_GT((first.positions() - previewEnd).cwiseAbs().maxCoeff(), 1e-7);  // the drape moved on (slowly: relaxation)
  const ResumeState state = first.resumeState();
  EXPECT_EQ(state.stage, Stage::Drape);
  Simulation edited(tablecloth("full", "denim"), state);
  EXPECT_TRUE(edited.resumed());
  EXPECT_EQ(edited.stage(), Stage::Drape);
  EXPECT_DOUBLE_EQ(edited.time(), previewEndTime);
  EXPECT_LT((edited.positions() - previewEnd).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Resume, DrapeWithoutPreviewStartsFromThePlacedGarment) {
  Simulation first(tablecloth("drape"));
  for (int i = 0; i < 3; ++i) first.step();
  Simulation edited(tablecloth("drape", "denim"), first.resumeState());
  EXPECT_FALSE(edited.resumed());
  EXPECT_DOUBLE_EQ(edited.time(), 0.0);
  EXPECT_EQ(edited.snapshot().stage, Stage::Placed);
}

TEST(Resume, RemeshedSceneStartsOver) {
  Simulation first(tablecloth("preview"));
  for (int i = 0; i < 3; ++i) first.step();
  Scene finer = tablecloth("preview");
  finer.settings.set("mesh.target_edge_length", "0.06", "test");
  Simulation edited(std::move(finer), first.resumeState());
  EXPECT_FALSE(edited.resumed());
  EXPECT_DOUBLE_EQ(edited.time(), 0.0);
}

TEST(Resume, EditedPatternCarriesTheStateToItsNewMesh) {
  Simulation first(tablecloth("preview"));
  for (int i = 0; i < 10; ++i) first.step();
  ResumeState state = first.resumeState();
  state.garment = std::make_shared<const Garment>(first.garment());
  // One corner of the square pulled 10 cm outward: the panel is meshed anew.
  Scene scene = tablecloth("preview");
  const Panel& panel = scene.pattern.panels[0];
  const Eigen::Vector2d centre = std::accumulate(panel.vertices.begin(), panel.vertices.end(), Eigen::Vector2d(0, 0)) /
                                 static_cast<double>(panel.vertices.size());
  const Eigen::Vector2d corner = panel.vertices[0];
  scene.pattern = moveVertex(scene.pattern, 0, 0,
                             corner + (corner - centre).normalized() * 0.1 * scene.pattern.unitsInMeter);
  Simulation edited(std::move(scene), state);
  const Garment& before = first.garment();
  const Garment& after = edited.garment();
  ASSERT_TRUE(after.vertexCount() != before.vertexCount() || after.triangles != before.triangles);
  EXPECT_TRUE(edited.resumed());
  EXPECT_EQ(edited.stage(), Stage::Preview);
  EXPECT_DOUBLE_EQ(edited.time(), first.time());
  // Where the new mesh has a vertex at the same pattern point as the old one (the corners that stayed), it carries
  // that vertex's position.
  const Eigen::MatrixX3d was = first.positions(), now = edited.positions();
  int shared = 0;
  for (int v = 0; v < after.vertexCount(); ++v)
    for (int u = 0; u < before.vertexCount(); ++u)
      if ((after.rest.row(v) - before.rest.row(u)).norm() < 1e-9) {
        ++shared;
        EXPECT_LT((now.row(v) - was.row(u)).norm(), 1e-9) << "vertex " << v;
      }
  EXPECT_GE(shared, 3);
  // Without the old mesh the state cannot be carried: the edited scene starts over.
  Scene again = tablecloth("preview");
  again.pattern = edited.scene().pattern;
  Simulation restarted(std::move(again), first.resumeState());
  EXPECT_FALSE(restarted.resumed());
  EXPECT_DOUBLE_EQ(restarted.time(), 0.0);
}

TEST(Simulation, ClearCancelLetsTheNextStepRun) {
  Simulation sim(tablecloth("drape"));
  sim.requestCancel();
  EXPECT_EQ(sim.step().status, StepStatus::Cancelled);
  sim.clearCancel();
  EXPECT_NE(sim.step().status, StepStatus::Cancelled);
  EXPECT_GT(sim.time(), 0.0);
}

TEST(Simulation, TimeLimitAlsoEndsThePreviewOfTheFullPipeline) {
  Scene scene = tablecloth("full");
  scene.settings.set("solver.max_sim_time", "0.05", "test");  // below solver.preview.max_time (0.5 s)
  Simulation sim(std::move(scene));
  int steps = 0;
  while (!sim.finished() && steps < 1000) {
    sim.step();
    ++steps;
  }
  EXPECT_EQ(sim.stage(), Stage::Preview);
  EXPECT_GE(sim.time(), 0.05 - 1e-9);
  EXPECT_LT(sim.time(), 0.05 + 0.02);  // stopped within a preview step of the limit
}

TEST(Simulation, MovingPinsFromTheSceneFile) {
  SceneRequest request;
  request.input = assetsDir() / ".." / "bench" / "scenes" / "twisting_square_coarse_denim.json";
  // Jersey: the pins (1e4 N/m springs) hold a soft knit within millimetres; denim at this coarse mesh pulls
  // them about 1.4 cm off their path.
  request.overrides = {{"mesh.target_edge_length", "0.1"}, {"solver.newton.h_max", "0.004"},
                       {"fabric.preset", "jersey_knit"}};
  Simulation sim(loadScene(request));
  while (sim.time() < 1.0) ASSERT_NE(sim.step().status, StepStatus::Diverged);
  // Half-way through the twist (t = 1 s) the rotating side has turned by 0.375 pi about the x axis: its vertices
  // (0.5, 1, z0) are at (0.5, 1 - z0 sin th, z0 cos th) up to the pin springs' lag.
  const double th = 0.75 * M_PI * (sim.time() - 0.5);
  const Eigen::MatrixX3d x = sim.positions();
  int checked = 0;
  for (int v : sim.pinned()) {
    const Eigen::Vector3d rest = sim.garment().positions.row(v).transpose();
    if (rest.x() < 0.49) continue;
    const Eigen::Vector3d expected(0.5, 1.0 - rest.z() * std::sin(th), rest.z() * std::cos(th));
    EXPECT_LT((x.row(v).transpose() - expected).norm(), 5e-3) << "vertex " << v;
    ++checked;
  }
  EXPECT_GT(checked, 5);
}

}  // namespace
}  // namespace drape::test
