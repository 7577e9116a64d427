#pragma once
// Shared pieces of the desktop-application tests: one QApplication per process (the offscreen platform when
// there is no display, so non-GL tests run anywhere), a dialog recorder, and scene helpers.
#include <gtest/gtest.h>

#include <QApplication>
#include <QCoreApplication>
#include <QMouseEvent>
#include <QSettings>
#include <QTest>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "drape/qt/main_window.h"
#include "drape/qt/scene_document.h"
#include "drape/qt/user_dialogs.h"
#include "shared_data.h"

namespace drape::test {

inline bool guiHaveDisplay() {
  const char* display = std::getenv("DISPLAY");
  const char* platform = std::getenv("QT_QPA_PLATFORM");
  return (display && *display) || (platform && *platform);
}

inline QApplication& guiApplication() {
  if (auto* existing = qobject_cast<QApplication*>(QCoreApplication::instance())) return *existing;
  static char name[] = "drape_gui_tests";
  static char platformFlag[] = "-platform";
  static char offscreen[] = "offscreen";
  static char* argvDisplay[] = {name, nullptr};
  static char* argvOffscreen[] = {name, platformFlag, offscreen, nullptr};
  static int argc = guiHaveDisplay() ? 1 : 3;
  QCoreApplication::setOrganizationName("DrapeTests");
  QCoreApplication::setApplicationName("drape_gui_tests");
  // Settings (the recent files) of this process alone: ctest runs the tests in parallel processes, and one that opens
  // a scene would otherwise change the recent files another is reading.
  const QString settings = QStringLiteral(DRAPE_TEST_OUTPUT_DIR "/qsettings/%1").arg(QCoreApplication::applicationPid());
  QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settings);
  QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, settings);
  static QApplication* app = new QApplication(argc, guiHaveDisplay() ? argvDisplay : argvOffscreen);
  return *app;
}

// Records what the window would have shown in a modal dialog.
class RecordingDialogs : public qt::UserDialogs {
 public:
  void showError(QWidget*, const QString& title, const QString& text) override { errors.push_back(text.toStdString()); }
  SaveChoice askSaveChanges(QWidget*, const QString&) override {
    ++saveQuestions;
    return answer;
  }
  std::vector<std::string> errors;
  int saveQuestions = 0;
  SaveChoice answer = SaveChoice::Cancel;
};

// A wait's bound only guards against a hang; a sanitized build (-DDRAPE_SANITIZE=ON) runs several times slower.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr int kWaitScale = 10;
#else
inline constexpr int kWaitScale = 1;
#endif

// A mouse event sent straight to widget (QTest's mouse moves carry no buttons, so a drag needs these): a press or
// release of the left button, or a move with `buttons` held.
inline void sendMouse(QWidget* widget, QEvent::Type type, const QPointF& at, Qt::MouseButtons buttons,
                      Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  const Qt::MouseButton button = type == QEvent::MouseMove ? Qt::NoButton : Qt::LeftButton;
  QMouseEvent event(type, at, widget->mapToGlobal(at), button, buttons, modifiers);
  QApplication::sendEvent(widget, &event);
}

// Processes events until done() or timeoutMs (times kWaitScale) pass; returns done().
inline bool waitUntil(const std::function<bool()>& done, int timeoutMs = 20000) {
  return QTest::qWaitFor(done, timeoutMs * kWaitScale);
}

// Settings that keep GUI tests fast: a coarse mesh (about 10 cm triangles).
inline std::vector<std::pair<std::string, std::string>> coarseOverrides() {
  return {{"mesh.target_edge_length", "0.1"}};
}

inline qt::SceneState coarseState(const std::filesystem::path& input) {
  qt::SceneState state;
  state.input = input;
  for (const auto& [key, value] : coarseOverrides()) state.overrides[key] = value;
  return state;
}

inline std::filesystem::path defaultScene() {
  return assetsDir() / "scenes" / "tablecloth.json";
}

// Settings under which a drape runs until it is paused: no simulated-time limit and no early stop. Tests that
// pause "after n reports" need them: the worker can outpace the UI thread and finish a coarse drape before the
// pause arrives.
inline std::vector<std::pair<std::string, std::string>> unendingDrapeOverrides() {
  return {{"solver.max_sim_time", "1000"}, {"solver.newton.rest_speed", "0"}};
}

// A shown main window with the coarse default scene (plus `extra` settings) open and its first snapshot
// received; null on failure.
inline std::unique_ptr<qt::MainWindow> openDefaultWindow(
    qt::UserDialogs* dialogs, const std::vector<std::pair<std::string, std::string>>& extra = {}) {
  auto window = std::make_unique<qt::MainWindow>(dialogs);
  auto overrides = coarseOverrides();
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  window->document()->setBaseOverrides(overrides);
  window->resize(1200, 800);
  window->show();
  if (!QTest::qWaitForWindowExposed(window.get()) || !window->openFile(defaultScene()) ||
      !waitUntil([&] { return window->currentSnapshot() != nullptr; }))
    return nullptr;
  return window;
}

}  // namespace drape::test
