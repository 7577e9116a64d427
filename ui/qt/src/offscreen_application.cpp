#include "offscreen_application.h"

#include <QThread>
#include <cstdio>
#include <string>

#include "drape/core/input_error.h"

namespace drape::qt {
namespace {

void quietQtMessages(QtMsgType type, const QMessageLogContext&, const QString& message) {
  if (type == QtCriticalMsg || type == QtFatalMsg) std::fprintf(stderr, "drape: Qt: %s\n", qPrintable(message));
}

}  // namespace

QuietQtMessages::QuietQtMessages() : m_previous(qInstallMessageHandler(quietQtMessages)) {}
QuietQtMessages::~QuietQtMessages() {
  qInstallMessageHandler(m_previous);
}

std::unique_ptr<QApplication> offscreenApplication(const std::filesystem::path& file, const char* what) {
  if (auto* existing = QCoreApplication::instance()) {
    if (!qobject_cast<QApplication*>(existing))
      throw InputError(file.string() + ": drawing " + what + " needs a QApplication, and this process has a " +
                       existing->metaObject()->className());
    if (QThread::currentThread() != existing->thread())
      throw InputError(file.string() + ": " + what + " must be drawn on the application's thread");
    return nullptr;
  }
  // QApplication takes the platform arguments out of argv and keeps argc and argv for its lifetime: they are static,
  // and filled again for each application.
  static char name[] = "drape";
  static char platformFlag[] = "-platform";
  static char offscreen[] = "offscreen";
  static char* argv[4];
  static int argc;
  argc = 3;
  argv[0] = name;
  argv[1] = platformFlag;
  argv[2] = offscreen;
  argv[3] = nullptr;
  return std::make_unique<QApplication>(argc, argv);
}

}  // namespace drape::qt
