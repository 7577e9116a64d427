// Crossings are pulled free (newton/contact/intersection_contour.h). The library t-shirt's seams draw its right sleeve
// through the front panel under the arm within its first few milliseconds. The preview, from the placed garment,
// has cleared what crossed 0.2 simulated seconds later. The drape, started from the tangled state itself (the drape
// without self-contact after 5 ms, 42 crossing pairs), too. Both keep the seams closed. Self-contact on, as a scene
// turns it on. The drape's steps stay whole while the seams close.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "drape/sim/drape_quality.h"
#include "drape/sim/simulation.h"
#include "pipeline_handoff_support.h"
#include "untangle_support.h"

namespace drape {
namespace {

double check(const Simulation& sim, const char* name) { return test::qualityValue(sim, name); }

// The t-shirt after 5 ms of the drape without self-contact: its sleeve through its front panel.
Eigen::MatrixX3d tangledShirt() {
  Simulation sim(test::libraryScene(
      "default.json",
      {{"contact.self_collision", "false"}, {"solver.stage", "drape"}, {"solver.max_sim_time", "0.005"}}));
  while (!sim.finished()) sim.step();
  return sim.positions();
}

void untanglesWithin(const char* stage, const Eigen::MatrixX3d& tangled) {
  Scene scene = test::libraryScene(
      "default.json", {{"contact.self_collision", "true"}, {"solver.stage", stage}, {"solver.max_sim_time", "0.2"}});
  const StagePlan plan = simulationSettingsFrom(scene).plan;
  Simulation sim(std::move(scene), startStateAt(plan, tangled));
  const double placed = check(sim, "self_intersections");
  while (!sim.finished()) ASSERT_NE(sim.step().status, StepStatus::Diverged) << stage;
  const double after = check(sim, "self_intersections");
  const double gap = check(sim, "seam_gap");
  std::printf("%s: %.0f crossing pairs at the start, %.0f 0.2 s later; largest seam gap %.2f mm\n", stage, placed,
              after, 1e3 * gap);
  EXPECT_GT(placed, 10.0) << stage;
  EXPECT_EQ(after, 0.0) << stage;
  EXPECT_LT(gap, 0.003) << stage;
}

TEST(Untangle, ThePreviewPullsASleeveOutOfTheFrontPanel) {
  Simulation sim(test::libraryScene(
      "default.json", {{"contact.self_collision", "true"}, {"solver.stage", "preview"}, {"solver.max_sim_time", "0.2"}}));
  double worst = 0.0;
  while (!sim.finished()) {
    ASSERT_NE(sim.step().status, StepStatus::Diverged);
    if (sim.time() < 0.05) worst = std::max(worst, check(sim, "self_intersections"));
  }
  const double after = check(sim, "self_intersections");
  std::printf("preview: up to %.0f crossing pairs in its first 50 ms, %.0f at 0.2 s; largest seam gap %.2f mm\n", worst,
              after, 1e3 * check(sim, "seam_gap"));
  EXPECT_GT(worst, 0.0);
  EXPECT_EQ(after, 0.0);
  EXPECT_LT(check(sim, "seam_gap"), 0.003);
}

TEST(Untangle, TheDrapePullsASleeveOutOfTheFrontPanel) {
  untanglesWithin("drape", tangledShirt());
}

// While the seams close (the drape's first 0.1 s from the placed garment, its relaxation), the pull held over each
// Newton step keeps the steps whole: about as few split steps with self-contact as without it. A pull that switched
// off inside a step wherever a crossing cleared split them by the dozen.
TEST(Untangle, TheDrapeClosesTheSeamsWithoutSplittingItsSteps) {
  const auto splits = [](const char* selfContact) {
    Simulation sim(test::libraryScene("default.json", {{"contact.self_collision", selfContact},
                                                        {"solver.stage", "drape"},
                                                        {"solver.max_sim_time", "0.1"}}));
    int total = 0;
    while (!sim.finished()) {
      const StepReport r = sim.step();
      EXPECT_NE(r.status, StepStatus::Diverged);
      if (r.status == StepStatus::Diverged) break;
      total += r.splits;
    }
    return total;
  };
  const int with = splits("true"), without = splits("false");
  std::printf("drape's first 0.1 s: %d split steps with self-contact, %d without\n", with, without);
  EXPECT_LE(with, without + 2);
}

// The preview's variant of tests/slow/untangle_drag_test.cpp, 14 cm deep: its few quasi-Newton iterations a step let
// a tip dragged much deeper spring back too slowly to be out within 0.2 s, with self-contact or without.
TEST(Untangle, ACurtainDraggedThroughAnotherComesBackWhenLetGoInThePreview) {
  test::draggedThroughComesBack("preview", 0.14);
}

// A drag that pushes one curtain into the other (tests/data/scenes/two_curtains.json, the back curtain free below its
// top edge; self-contact on), as a designer's cursor would: 6 cm back at 0.4 m/s, then held. The back curtain is
// pushed along. In the drape the cloth never passes through, at any step. The preview's longer steps (8 ms: 3 mm of
// drag, more than the contact's 2 mm thickness) may let a few triangles through, never for two steps running.
std::vector<double> crossingsWhileDraggingIntoTheBackCurtain(const char* stage) {
  SceneRequest request;
  request.input = test::testDataDir() / "scenes" / "two_curtains.json";
  request.overrides = {{"solver.stage", stage}, {"solver.max_sim_time", "1"}};
  Simulation sim(loadScene(request));
  const Eigen::MatrixX3d placed = sim.positions();
  int front = 0, back = 0;
  (placed.rowwise() - Eigen::RowVector3d(0.0, 1.3, 0.0)).rowwise().squaredNorm().minCoeff(&front);
  (placed.rowwise() - Eigen::RowVector3d(0.0, 1.3, -0.03)).rowwise().squaredNorm().minCoeff(&back);
  std::vector<double> crossings;
  while (sim.time() < 0.3 - 1e-9) {
    sim.setDrag(front, Eigen::Vector3d(0.0, 1.3, -std::min(0.06, 0.4 * sim.time())));
    EXPECT_NE(sim.step().status, StepStatus::Diverged) << stage;
    crossings.push_back(check(sim, "self_intersections"));
  }
  const Eigen::MatrixX3d x = sim.positions();
  std::printf("%s, dragged to 3 cm behind the back curtain: front centre at z = %.1f mm, back centre at %.1f mm; at "
              "most %.0f crossing pairs in %zu steps\n",
              stage, 1e3 * x(front, 2), 1e3 * x(back, 2), *std::max_element(crossings.begin(), crossings.end()),
              crossings.size());
  EXPECT_LT(x(front, 2), -0.05) << stage << ": the drag reached past where the back curtain hung";
  EXPECT_LT(x(back, 2), x(front, 2)) << stage << ": the back curtain stays behind";
  return crossings;
}

TEST(Untangle, ADragPushesTheClothBehindAlongAndNeverThroughIt) {
  for (double c : crossingsWhileDraggingIntoTheBackCurtain("drape")) ASSERT_EQ(c, 0.0);
  const std::vector<double> preview = crossingsWhileDraggingIntoTheBackCurtain("preview");
  for (std::size_t k = 1; k < preview.size(); ++k)
    EXPECT_TRUE(preview[k - 1] == 0.0 || preview[k] == 0.0) << "crossed at steps " << k - 1 << " and " << k;
  EXPECT_EQ(preview.back(), 0.0);
}

}  // namespace
}  // namespace drape
