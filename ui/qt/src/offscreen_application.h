#pragma once
// Private: what headless drawing with Qt's widgets module needs (QGraphicsScene, QChart): a QApplication on the
// offscreen platform when the process has none, and Qt's chatter kept off stderr meanwhile.
#include <QApplication>
#include <filesystem>
#include <memory>

namespace drape::qt {

// Qt's debug and warning messages while drawing ("XDG_RUNTIME_DIR not set" on a headless machine) say nothing the
// user can act on; critical and fatal ones still reach stderr. Installed for the object's lifetime.
class QuietQtMessages {
 public:
  QuietQtMessages();
  ~QuietQtMessages();
  QuietQtMessages(const QuietQtMessages&) = delete;
  QuietQtMessages& operator=(const QuietQtMessages&) = delete;

 private:
  QtMessageHandler m_previous;
};

// A QApplication on the offscreen platform when the process has none, null when it has one. The platform comes as
// an argument, not through QT_QPA_PLATFORM, so that the environment of the process is left as it was. Throws
// InputError naming file and what is drawn when the process has another kind of application or this is not its
// thread.
std::unique_ptr<QApplication> offscreenApplication(const std::filesystem::path& file, const char* what);

}  // namespace drape::qt
