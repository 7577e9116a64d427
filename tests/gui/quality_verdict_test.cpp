// A finished drape shows its quality verdict: the Statistics dock lists each check with its value and threshold
// (the stretch against one computed from the finished snapshot), and the Log has a warning per failed check.
#include <QAction>
#include <QPlainTextEdit>

#include "drape/geometry/strain.h"
#include "drape/qt/main_window.h"
#include "drape/qt/simulation_controller.h"
#include "drape/qt/statistics_panel.h"
#include "gui_test_support.h"

namespace drape::test {
namespace {

TEST(QualityVerdict, FinishedDrapeShowsTheVerdictInTheStatisticsDockAndTheLog) {
  if (!guiHaveDisplay()) GTEST_SKIP() << "no display: run under xvfb-run -a";
  guiApplication();
  RecordingDialogs dialogs;
  // The coarse tablecloth cut short at 0.03 s: it ends at the time limit, not at rest, so the verdict fails there.
  auto window = openDefaultWindow(&dialogs, {{"solver.max_sim_time", "0.03"}});
  ASSERT_NE(window, nullptr);
  qt::StatisticsPanel* panel = window->statisticsPanel();
  EXPECT_EQ(panel->qualityVerdict(), "-");
  EXPECT_EQ(panel->qualityRows(), 0);

  window->simulationActions().drape->trigger();
  ASSERT_TRUE(waitUntil([&] { return window->controller()->runState() == qt::RunState::Finished; }));
  ASSERT_TRUE(waitUntil([&] { return panel->qualityRows() > 0; }));
  QTest::qWait(100);  // the finished snapshot

  // The tablecloth has a sphere collider: every check, the collider's included.
  const QStringList expected = {
      "max_strain",         "inside_fraction", "penetration_depth", "near_skin_fraction", "outward_faces",
      "self_intersections", "seam_gap", "at_rest"};
  ASSERT_EQ(panel->qualityRows(), expected.size());
  for (int row = 0; row < expected.size(); ++row) {
    EXPECT_EQ(panel->qualityCell(row, 0), expected[row]);
    EXPECT_FALSE(panel->qualityCell(row, 1).isEmpty());
    EXPECT_FALSE(panel->qualityCell(row, 2).isEmpty());
  }
  EXPECT_EQ(panel->qualityCell(7, 1), "no");  // at_rest
  EXPECT_EQ(panel->qualityCell(7, 2), "yes");
  EXPECT_TRUE(panel->qualityVerdict().startsWith("failed")) << panel->qualityVerdict().toStdString();
  // The stretch shown is the finished garment's.
  const auto snapshot = window->currentSnapshot();
  const Eigen::VectorXd stretch = triangleStretch(snapshot->uvs, snapshot->positions, snapshot->triangles);
  EXPECT_EQ(panel->qualityCell(0, 1), QStringLiteral("%1 %").arg(stretch.maxCoeff() * 100.0, 0, 'f', 2));
  EXPECT_EQ(panel->qualityCell(0, 2), "100.00 %");
  const QString log = window->logView()->toPlainText();
  EXPECT_NE(log.indexOf("quality: at_rest: the run ended with MaxSimTime"), -1) << log.toStdString();

  // Reset clears the verdict.
  window->simulationActions().reset->trigger();
  ASSERT_TRUE(waitUntil([&] { return window->controller()->runState() == qt::RunState::Ready; }));
  EXPECT_EQ(panel->qualityVerdict(), "-");
  EXPECT_EQ(panel->qualityRows(), 0);
  dialogs.answer = qt::UserDialogs::SaveChoice::Discard;
  window->close();
}

}  // namespace
}  // namespace drape::test
