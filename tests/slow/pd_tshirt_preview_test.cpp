// Issue 6: the preview of the t-shirt on the default mannequin settles without NaN and without vertices inside the
// body, and the full pipeline ends in the Newton drape. It needs the preview's step halving: at a fixed 1/120 s the
// L-G loop never converges (armpit vertices cycle between contact targets on the crease's two surfaces), the
// triangles stretch and the shirt falls through the body. Runs ~1-2 min.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "drape/collision/avatar_collider.h"
#include "drape/geometry/strain.h"
#include "drape/scene/scene.h"
#include "drape/sim/simulation.h"
#include "drape/sim/snapshot_builder.h"
#include "shared_data.h"

namespace drape::test {
namespace {

// The default scene (t-shirt on the default mannequin) with the given setting overrides.
Scene defaultScene(std::vector<std::pair<std::string, std::string>> overrides) {
  SceneRequest request;
  request.input = assetsDir() / "scenes" / "default.json";
  request.overrides = std::move(overrides);
  return loadScene(request);
}

struct OffBody {
  int inside = 0;  // deeper inside the body than the contact thickness
  int away = 0;    // more than 10 cm off it: a worn t-shirt hangs at most a few centimetres off the body
};

OffBody offBody(const collision::AvatarCollider& body, const Simulation& sim, const Eigen::MatrixX3d& x) {
  OffBody count;
  for (int v = 0; v < x.rows(); ++v) {
    const double d = body.signedDistance(x.row(v).transpose());
    count.inside += d < -sim.contactThickness();
    count.away += d > 0.1;
  }
  return count;
}

}  // namespace

// The first two tests run the preview without its quasi-static start (relaxation_time 0): their stretch and slide
// bounds are set for that start. With the default quasi-static start the sewn preview's shoulders stretch to 99 %
// and the shirt drops 25 mm in the 0.5 s after it is sewn (the under-converged PD elasticity carrying the whole shirt
// from the shoulders, instead of a back hem perched on the small of the back); QuasiStaticStartKeepsTheBackHemDown
// covers the default.
TEST(PdTshirtPreview, DefaultSceneStaysOnTheBodyAndHandsOverToTheDrape) {
  Simulation sim(defaultScene({{"solver.stage", "full"}, {"solver.preview.relaxation_time", "0"}}));
  const collision::AvatarCollider body(mergedColliders(sim.scene()));
  // Closing the seams stretches triangles along them for a few hundredths of a second; after that phase (0.1 s)
  // the largest stretch stays moderate, and the shirt does not slide off.
  double worstStrain = 0.0, lastStrain = 0.0;
  int steps = 0;
  while (!sim.finished() && sim.stage() == Stage::Preview) {
    const StepReport r = sim.step();
    ASSERT_NE(r.status, StepStatus::Diverged) << "t = " << r.time;
    if (r.time > 0.1) worstStrain = std::max(worstStrain, r.maxStrain);
    lastStrain = r.maxStrain;
    ++steps;
  }
  EXPECT_LT(worstStrain, 0.6);
  EXPECT_LT(lastStrain, 0.5);
  EXPECT_GT(steps, 10);
  const Eigen::MatrixX3d x = sim.positions();
  ASSERT_TRUE(x.allFinite());
  const OffBody off = offBody(body, sim, x);
  EXPECT_EQ(off.inside, 0);
  EXPECT_EQ(off.away, 0);
  // The full pipeline continues in the Newton drape and does not diverge there.
  for (int i = 0; i < 200 && !sim.finished(); ++i) ASSERT_NE(sim.step().status, StepStatus::Diverged);
  EXPECT_EQ(sim.stage(), Stage::Drape);
}

// Once sewn (solver.preview.sewn_gap), the preview holds contact targets within a step and lets the cloth's tension
// load friction: the steps converge at the paper's 1/120 s, and the shirt stays where it is. Without the sewn regime
// (sewn_gap 0, from the same sewn state), 1/120 s steps hit the L-G cap and the shirt slides down the body. The
// scenes' default step is 1/480 s; this test keeps the paper's step, its subject.
TEST(PdTshirtPreview, SewnShirtConvergesAtThePapersStepAndStaysPut) {
  Simulation sim(defaultScene({{"solver.stage", "preview"},
                               {"solver.max_sim_time", "3"},
                               {"solver.preview.relaxation_time", "0"},
                               {"solver.preview.time_step", "0.008333333333333333"}}));
  const collision::AvatarCollider body(mergedColliders(sim.scene()));
  double sewnAt = -1.0;
  while (!sim.finished()) {
    const StepReport r = sim.step();
    ASSERT_NE(r.status, StepStatus::Diverged) << "t = " << r.time;
    if (r.sewn) {
      sewnAt = r.time;
      break;
    }
  }
  ASSERT_GE(sewnAt, 0.0) << "the t-shirt never counted as sewn";
  EXPECT_LT(sewnAt, 1.0);
  const Eigen::MatrixX3d start = sim.positions();
  const double paperStep = 1.0 / 120.0;
  int steps = 0, atPaperStep = 0, capped = 0, late = 0, lateAtPaperStep = 0;
  long iterations = 0;
  double time = sewnAt, worstStrain = 0.0;
  while (!sim.finished() && time < sewnAt + 0.5) {
    const StepReport r = sim.step();
    ASSERT_NE(r.status, StepStatus::Diverged) << "t = " << r.time;
    EXPECT_TRUE(r.sewn);
    time = r.time;
    ++steps;
    iterations += r.iterations;
    const bool paper = std::abs(r.h - paperStep) < 1e-12;
    atPaperStep += paper;
    if (time > sewnAt + 0.25) {
      ++late;
      lateAtPaperStep += paper;
    }
    capped += r.status == StepStatus::MaxIterations;
    worstStrain = std::max(worstStrain, r.maxStrain);
  }
  const Eigen::MatrixX3d x = sim.positions();
  ASSERT_TRUE(x.allFinite());
  const double meanDrop = (start.col(1) - x.col(1)).mean();
  const double meanMove = (x - start).rowwise().norm().mean();
  std::printf(
      "[ PdTshirtPreview ] sewn at t = %.3f s; then %d steps to t = %.3f s: %d at 1/120 s, %d capped, %.2f "
      "L-G iterations per step; mean move %.1f mm, mean drop %.1f mm, largest stretch %.0f %%\n",
      sewnAt, steps, time, atPaperStep, capped, static_cast<double>(iterations) / std::max(steps, 1), 1e3 * meanMove,
      1e3 * meanDrop, 100.0 * worstStrain);
  EXPECT_GE(steps, 20);
  // The assembly's halved steps grow back (grow_after_steps converged steps per doubling); then all are at 1/120 s.
  EXPECT_GT(late, 20);
  EXPECT_EQ(lateAtPaperStep, late);
  EXPECT_LE(capped, steps / 20);
  EXPECT_LT(static_cast<double>(iterations) / steps, 5.0);
  EXPECT_LT(meanDrop, 0.015);
  EXPECT_LT(worstStrain, 0.6);
  const OffBody off = offBody(body, sim, x);
  EXPECT_EQ(off.inside, 0);
  EXPECT_EQ(off.away, 0);
}

// Without the quasi-static start, the stitches' pull of the first steps, carried on as velocity, throws the back hem
// up onto the small of the back, where the drape keeps it. With it (the default), the hem comes down.
TEST(PdTshirtPreview, QuasiStaticStartKeepsTheBackHemDown) {
  Simulation sim(defaultScene({{"solver.stage", "full"}}));
  const collision::AvatarCollider body(mergedColliders(sim.scene()));
  // The back panel's hem: the lowest placed vertices behind the body.
  const Eigen::MatrixX3d placed = sim.positions();
  const double hemHeight = placed.col(1).minCoeff();
  std::vector<int> backHem;
  for (int v = 0; v < placed.rows(); ++v)
    if (placed(v, 2) < 0.0 && placed(v, 1) < hemHeight + 0.02) backHem.push_back(v);
  ASSERT_GT(backHem.size(), 5u);
  const auto hemMean = [&] {
    double mean = 0.0;
    for (int v : backHem) mean += sim.positions()(v, 1) / static_cast<double>(backHem.size());
    return mean;
  };
  double worstStrain = 0.0, highestHem = -1e9;
  while (!sim.finished() && sim.stage() == Stage::Preview) {
    const StepReport r = sim.step();
    ASSERT_NE(r.status, StepStatus::Diverged) << "t = " << r.time;
    if (r.time > 0.1) worstStrain = std::max(worstStrain, r.maxStrain);
    highestHem = std::max(highestHem, hemMean());
  }
  EXPECT_TRUE(sim.previewFailure().empty()) << sim.previewFailure();
  const double handedOver = hemMean();
  // Mean height of the back hem, placed at 0.815 m (Newton alone drapes it at 0.87 m). Thrown, it reached 1.05 m and
  // was still at 0.97 m at the hand-over; now 0.95 m at most and 0.88 m at the hand-over.
  EXPECT_LT(highestHem, hemHeight + 0.2) << "the back hem flew up";
  EXPECT_LT(handedOver, hemHeight + 0.1) << "the back hem stayed up";
  EXPECT_LT(worstStrain, 1.2);  // 99 % at the shoulders (see above)
  const Eigen::MatrixX3d x = sim.positions();
  ASSERT_TRUE(x.allFinite());
  const OffBody off = offBody(body, sim, x);
  EXPECT_EQ(off.inside, 0);
  EXPECT_EQ(off.away, 0);
  for (int i = 0; i < 50 && !sim.finished(); ++i) ASSERT_NE(sim.step().status, StepStatus::Diverged);
  EXPECT_EQ(sim.stage(), Stage::Drape);
}

// At 1 cm the preview cannot sew the t-shirt by itself: every step hits the L-G cap at 1/480 s, the armhole
// stitches stay open and the arms pass through the sleeves. It sews it on a 2 cm meshing of the pattern
// (solver.preview.assembly_edge_length) and carries the sewn garment over to the 1 cm mesh, where it counts as sewn
// again and keeps the shirt on the body.
TEST(PdTshirtPreview, FineShirtIsSewnOnACoarserMeshAndCarriedOver) {
  Simulation sim(
      defaultScene({{"solver.stage", "preview"}, {"mesh.target_edge_length", "0.01"}, {"solver.max_sim_time", "3"}}));
  const collision::AvatarCollider body(mergedColliders(sim.scene()));
  ASSERT_TRUE(sim.assembling());
  ASSERT_GT(sim.garment().vertexCount(), 10000);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(sim.step().assembly);
  {  // An edit during the assembly starts it over: its state is the coarse mesh's, carried, and not sewn.
    const ResumeState state = sim.resumeState();
    EXPECT_TRUE(state.assembling);
    Simulation again(sim.scene(), state);
    EXPECT_FALSE(again.resumed());
    EXPECT_TRUE(again.assembling());
    // Snapshots and drags go through the transfer while the assembly runs.
    const Snapshot snap = sim.snapshot();
    EXPECT_EQ(snap.positions.rows(), sim.garment().vertexCount());
    EXPECT_EQ(snap.vertexContact.size(), sim.garment().vertexCount());
    EXPECT_EQ(snap.stage, Stage::Preview);
    Simulation free(sim.scene(), state);
    const Eigen::Vector3d grabbed = again.positions().row(100).transpose();
    again.setDrag(100, grabbed + Eigen::Vector3d(0.0, 0.0, 0.05));
    EXPECT_NE(again.step().status, StepStatus::Diverged);
    EXPECT_NE(free.step().status, StepStatus::Diverged);
    EXPECT_GT(again.positions()(100, 2), free.positions()(100, 2) + 1e-4);  // pulled forward by the drag
  }
  while (!sim.finished() && sim.assembling()) {
    const StepReport r = sim.step();
    ASSERT_NE(r.status, StepStatus::Diverged) << "t = " << r.time;
  }
  ASSERT_FALSE(sim.assembling()) << "the coarse assembly never counted as sewn";
  const double handover = sim.time();
  EXPECT_LT(handover, 0.5);
  auto largestGap = [&](const Eigen::MatrixX3d& x) {
    double gap = 0.0;
    for (const auto& [a, b] : sim.garment().stitchPairs) gap = std::max(gap, (x.row(a) - x.row(b)).norm());
    return gap;
  };
  const double gapAtHandover = largestGap(sim.positions());
  EXPECT_LT(gapAtHandover, 3e-3);
  double sewnAt = -1.0, time = handover;
  int steps = 0, capped = 0;
  while (!sim.finished() && time < std::max(sewnAt, handover + 0.3) + 0.2) {
    const StepReport r = sim.step();
    ASSERT_NE(r.status, StepStatus::Diverged) << "t = " << r.time;
    EXPECT_FALSE(r.assembly);
    if (r.sewn && sewnAt < 0.0) sewnAt = r.time;
    time = r.time;
    ++steps;
    capped += r.status == StepStatus::MaxIterations;
  }
  ASSERT_GE(sewnAt, 0.0) << "the 1 cm shirt never counted as sewn after the hand-over";
  EXPECT_LT(sewnAt, handover + 0.3);
  const Eigen::MatrixX3d x = sim.positions();
  ASSERT_TRUE(x.allFinite());
  Eigen::VectorXd stretch = triangleStretch(sim.garment().rest, x, sim.garment().triangles);
  std::sort(stretch.begin(), stretch.end());
  const double p99 = stretch[static_cast<Eigen::Index>(0.99 * (stretch.size() - 1))];
  const OffBody off = offBody(body, sim, x);
  std::printf(
      "[ PdTshirtPreview ] 1 cm shirt: carried over at t = %.3f s (largest stitch gap %.2f mm), sewn at %.3f "
      "s; at t = %.3f s after %d steps (%d capped): stretch p99 %.0f %%, largest %.0f %%\n",
      handover, 1e3 * gapAtHandover, sewnAt, time, steps, capped, 100.0 * p99, 100.0 * stretch[stretch.size() - 1]);
  EXPECT_LT(p99, 0.4);
  EXPECT_LT(stretch[stretch.size() - 1], 1.2);
  EXPECT_LE(capped, steps / 10);
  EXPECT_EQ(off.inside, 0);
  EXPECT_EQ(off.away, 0);
}

// Before the shirt is sewn, contact targets are held within steps of at most 1/480 s
// (solver.preview.hold_targets_step). At that step a held target, which pins its vertex for the step, costs the
// closing seams nothing, and it stops armpit vertices cycling between targets: fewer L-G iterations and no capped
// step. Over longer steps the pins tore the shirt (700 % at 1/120 s), so there the targets are not held until it is
// sewn: a run at 1/120 s without halvings is the same with and without the setting.
TEST(PdTshirtPreview, TargetsHeldOnlyInShortStepsBeforeTheShirtIsSewn) {
  struct Run {
    long iterations = 0;
    int steps = 0, capped = 0;
    double sewnAt = -1.0, worstStrain = 0.0;
    Eigen::MatrixX3d x;
  };
  const auto run = [](const std::string& holdStep, const std::string& timeStep, double until) {
    Simulation sim(defaultScene({{"solver.stage", "preview"},
                                 {"solver.preview.time_step", timeStep},
                                 {"solver.preview.hold_targets_step", holdStep}}));
    Run r;
    while (!sim.finished() && sim.time() < until) {
      const StepReport s = sim.step();
      EXPECT_NE(s.status, StepStatus::Diverged) << "t = " << s.time;
      r.iterations += s.iterations;
      ++r.steps;
      r.capped += s.status == StepStatus::MaxIterations;
      if (s.sewn && r.sewnAt < 0.0) r.sewnAt = s.time;
      if (s.time > 0.1) r.worstStrain = std::max(r.worstStrain, s.maxStrain);
    }
    r.x = sim.positions();
    return r;
  };
  const std::string shortStep = "0.0020833333333333333";
  const Run held = run(shortStep, shortStep, 0.35);
  const Run free = run("0", shortStep, 0.35);
  std::printf(
      "[ PdTshirtPreview ] to t = 0.35 s at 1/480 s: held %ld L-G iterations in %d steps (%d capped, sewn at %.3f s, "
      "largest stretch %.0f %%); not held %ld in %d (%d capped, sewn at %.3f s, %.0f %%)\n",
      held.iterations, held.steps, held.capped, held.sewnAt, 100.0 * held.worstStrain, free.iterations, free.steps,
      free.capped, free.sewnAt, 100.0 * free.worstStrain);
  EXPECT_LT(static_cast<double>(held.iterations), 0.8 * static_cast<double>(free.iterations));
  EXPECT_LE(held.capped, free.capped);
  ASSERT_GE(held.sewnAt, 0.0) << "the held run never counted as sewn";
  EXPECT_LT(held.worstStrain, 0.6);
  ASSERT_TRUE(held.x.allFinite());

  // At 1/120 s (no halvings) the setting changes nothing until the shirt is sewn.
  const std::string paperStep = "0.008333333333333333";
  Simulation a(defaultScene({{"solver.stage", "preview"}, {"solver.preview.time_step", paperStep},
                             {"solver.preview.max_halvings", "0"}}));
  Simulation b(defaultScene({{"solver.stage", "preview"}, {"solver.preview.time_step", paperStep},
                             {"solver.preview.max_halvings", "0"}, {"solver.preview.hold_targets_step", "0"}}));
  for (int i = 0; i < 6; ++i) {
    ASSERT_FALSE(a.step().sewn);
    b.step();
  }
  EXPECT_EQ((a.positions() - b.positions()).cwiseAbs().maxCoeff(), 0.0);
  Simulation c(defaultScene({{"solver.stage", "preview"}, {"solver.preview.time_step", paperStep},
                             {"solver.preview.max_halvings", "0"}, {"solver.preview.hold_targets_step", paperStep}}));
  for (int i = 0; i < 6; ++i) c.step();
  EXPECT_GT((c.positions() - b.positions()).cwiseAbs().maxCoeff(), 1e-4) << "holding at 1/120 s changed nothing";
}

}  // namespace drape::test
