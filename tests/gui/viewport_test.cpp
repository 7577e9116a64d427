// The Qt viewport draws through the same renderer as the headless path: one frame grabbed from a
// QOpenGLWidget under Xvfb (xvfb-run -a ctest) matches the EGL image of the same snapshot and camera.
#include <gtest/gtest.h>

#include <QApplication>
#include <QImage>
#include <QMouseEvent>
#include <QTest>
#include <cstdlib>
#include <cstring>

#include "synthetic_scenes.h"
#include "drape/qt/viewport_widget.h"
#include "drape/render/headless.h"
#include "drape/render/image_compare.h"
#include "drape/render/png_io.h"
#include "shared_data.h"

namespace drape::test {
namespace {

QApplication& application() {
  static int argc = 1;
  static char name[] = "drape_gui_tests";
  static char* argv[] = {name, nullptr};
  if (auto* existing = qobject_cast<QApplication*>(QCoreApplication::instance())) return *existing;
  static QApplication* app = new QApplication(argc, argv);
  return *app;
}

bool haveDisplay() {
  const char* display = std::getenv("DISPLAY");
  const char* platform = std::getenv("QT_QPA_PLATFORM");
  return (display && *display) || (platform && *platform);
}

render::Image toImage(const QImage& source) {
  const QImage rgba = source.convertToFormat(QImage::Format_RGBA8888);
  render::Image image(rgba.width(), rgba.height());
  for (int y = 0; y < rgba.height(); ++y)
    std::memcpy(image.at(0, y), rgba.constScanLine(y), static_cast<size_t>(rgba.width()) * 4);
  return image;
}

class ViewportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!haveDisplay()) GTEST_SKIP() << "no display: run under xvfb-run -a";
    application();
  }
};

TEST_F(ViewportTest, FrameMatchesTheEglImageOfTheSameSnapshot) {
  const Snapshot scene = skirtScene();
  render::RenderOptions options;
  options.mode = render::DisplayMode::Strain;
  options.wireframeOverlay = true;

  qt::ViewportWidget widget;
  widget.resize(256, 256);
  widget.setSnapshot(scene);
  widget.setRenderOptions(options);
  widget.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&widget));
  widget.setViewPreset(render::ViewPreset::ThreeQuarter);
  const QImage grabbed = widget.grabFramebuffer();
  ASSERT_TRUE(widget.lastError().isEmpty()) << widget.lastError().toStdString();
  ASSERT_EQ(grabbed.width(), 256) << "device pixel ratio must be 1 under Xvfb";
  const render::Image qtImage = toImage(grabbed);

  options.width = options.height = 256;
  const render::Image eglImage = render::renderSnapshot(scene, widget.camera(), options);
  const render::CompareResult r = render::compareImages(eglImage, qtImage, {8, 0.999});
  if (!r.matches) {
    render::writePng(testOutputDir() / "viewport_qt.png", qtImage);
    render::writePng(testOutputDir() / "viewport_egl.png", eglImage);
    render::writePng(testOutputDir() / "viewport_diff.png", r.diff);
  }
  EXPECT_TRUE(r.matches) << r.summary();
  // the frame shows the scene, not only the background
  const render::Image empty = render::renderSnapshot(Snapshot{}, widget.camera(), options);
  EXPECT_GT(render::compareImages(empty, qtImage).mismatchedPixels, 5000);
}

TEST_F(ViewportTest, MouseOrbitPanAndZoomMoveTheCamera) {
  qt::ViewportWidget widget;
  widget.resize(200, 200);
  widget.setSnapshot(tableclothScene(8, 1.0, 1));
  widget.show();
  ASSERT_TRUE(QTest::qWaitForWindowExposed(&widget));
  widget.setViewPreset(render::ViewPreset::Front);
  const render::Camera start = widget.camera();
  const double distance = (start.eye - start.target).norm();

  QTest::mousePress(&widget, Qt::LeftButton, Qt::NoModifier, QPoint(100, 100));
  QMouseEvent move(QEvent::MouseMove, QPointF(150, 100), widget.mapToGlobal(QPointF(150, 100)), Qt::LeftButton,
                   Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(&widget, &move);
  QTest::mouseRelease(&widget, Qt::LeftButton, Qt::NoModifier, QPoint(150, 100));
  const render::Camera orbited = widget.camera();
  EXPECT_TRUE(orbited.target.isApprox(start.target));
  EXPECT_NEAR((orbited.eye - orbited.target).norm(), distance, 1e-9);  // orbit keeps the distance
  EXPECT_GT((orbited.eye - start.eye).norm(), 0.1 * distance);

  QTest::mousePress(&widget, Qt::RightButton, Qt::NoModifier, QPoint(100, 100));
  QMouseEvent drag(QEvent::MouseMove, QPointF(100, 140), widget.mapToGlobal(QPointF(100, 140)), Qt::RightButton,
                   Qt::RightButton, Qt::NoModifier);
  QApplication::sendEvent(&widget, &drag);
  QTest::mouseRelease(&widget, Qt::RightButton, Qt::NoModifier, QPoint(100, 140));
  const render::Camera panned = widget.camera();
  EXPECT_GT((panned.target - orbited.target).norm(), 1e-3);
  EXPECT_TRUE((panned.eye - panned.target).isApprox(orbited.eye - orbited.target, 1e-9));  // pan translates

  QWheelEvent wheel(QPointF(100, 100), widget.mapToGlobal(QPointF(100, 100)), QPoint(), QPoint(0, 120),
                    Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
  QApplication::sendEvent(&widget, &wheel);
  EXPECT_NEAR((widget.camera().eye - widget.camera().target).norm(), 0.85 * distance, 1e-6);

  widget.frameAll();
  const render::Camera framed = widget.camera();
  EXPECT_TRUE(framed.target.isApprox(widget.snapshot().bounds().center()));
}

}  // namespace
}  // namespace drape::test
