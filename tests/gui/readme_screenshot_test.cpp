// Writes the README screenshot (docs/screenshot.png) when DRAPE_SCREENSHOT names the output file:
//   DRAPE_SCREENSHOT=docs/screenshot.png xvfb-run -a -s "-screen 0 1600x1000x24"
//     build/tests/drape_gui_tests --gtest_filter='ReadmeScreenshot.*'   (one command, on one line)
// DRAPE_SCREENSHOT_SCENE picks the scene (default: assets/scenes/tablecloth.json; the README's is default.json, the
// t-shirt, with its first seam selected in the pattern view beside the drape), DRAPE_SCREENSHOT_TIME the
// simulated time to drape before the picture (default 1.5 s), DRAPE_SCREENSHOT_EDGE the mesh edge length (m).
// Skipped otherwise: it takes minutes.
#include <QDockWidget>
#include <QImage>
#include <QScreen>

#include "drape/qt/main_window.h"
#include "drape/qt/pattern_sheet.h"
#include "drape/qt/scene_document.h"
#include "drape/qt/simulation_controller.h"
#include "drape/qt/statistics_panel.h"
#include "drape/qt/viewport_widget.h"
#include "gui_test_support.h"

namespace drape::test {
namespace {

TEST(ReadmeScreenshot, DrapedGarmentInTheMainWindow) {
  const char* output = std::getenv("DRAPE_SCREENSHOT");
  if (!output || !*output) GTEST_SKIP() << "set DRAPE_SCREENSHOT=path.png to write the README screenshot";
  if (!guiHaveDisplay()) GTEST_SKIP() << "no display: run under xvfb-run -a";
  guiApplication();
  const char* sceneEnv = std::getenv("DRAPE_SCREENSHOT_SCENE");
  const char* timeEnv = std::getenv("DRAPE_SCREENSHOT_TIME");
  const std::filesystem::path scene = sceneEnv && *sceneEnv ? std::filesystem::path(sceneEnv) : defaultScene();
  const double until = timeEnv && *timeEnv ? std::stod(timeEnv) : 1.5;

  RecordingDialogs dialogs;
  dialogs.answer = qt::UserDialogs::SaveChoice::Discard;
  qt::MainWindow window(&dialogs);
  if (const char* edge = std::getenv("DRAPE_SCREENSHOT_EDGE"); edge && *edge)
    window.document()->setBaseOverrides({{"mesh.target_edge_length", edge}});
  window.resize(1500, 920);
  window.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&window));
  ASSERT_TRUE(window.openFile(scene)) << (dialogs.errors.empty() ? "" : dialogs.errors[0]);
  ASSERT_TRUE(waitUntil([&] { return window.currentSnapshot() != nullptr; }));
  window.simulationActions().drape->trigger();
  ASSERT_TRUE(waitUntil(
      [&] {
        auto s = window.currentSnapshot();
        return (s && s->time >= until) || window.controller()->runState() == qt::RunState::Finished;
      },
      30 * 60 * 1000));
  window.simulationActions().pause->trigger();
  ASSERT_TRUE(waitUntil([&] { return window.controller()->runState() != qt::RunState::Running; }));
  window.viewport()->setViewPreset(render::ViewPreset::ThreeQuarter);
  // The linked selection on show: the first seam, in the pattern view and along the garment.
  const Pattern& pattern = window.document()->scene().pattern;
  if (!pattern.stitches.empty())
    window.patternSheet()->itemClicked({pattern.stitches[0].a.panel, pattern.stitches[0].a.edge, 0});
  QTest::qWait(500);
  // What the screen shows: QWidget::grab leaves out what the viewport paints over its OpenGL image (the seam).
  const QImage image = QGuiApplication::primaryScreen()->grabWindow(window.winId()).toImage();
  ASSERT_FALSE(image.isNull());
  ASSERT_TRUE(image.save(QString::fromUtf8(output), "PNG"));
  EXPECT_TRUE(dialogs.errors.empty()) << dialogs.errors[0];
}

}  // namespace
}  // namespace drape::test
