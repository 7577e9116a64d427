// `drape [SCENE]`: the desktop application. Without a scene it opens assets/scenes/default.json.
#include "gui_entry.h"

#if DRAPE_WITH_GUI
#include <QApplication>
#include <QStyleFactory>
#include <QSurfaceFormat>
#include <QTimer>

#include "drape/core/assets.h"
#include "drape/qt/main_window.h"
#include "drape/qt/scene_document.h"
#else
#include <iostream>
#endif

namespace drape::app {

#if DRAPE_WITH_GUI
int runGui(int argc, char** argv, const CliOptions& options) {
  // OpenGL 3.3 core for the viewport (drape::render needs it), multisampling done by the renderer.
  QSurfaceFormat format;
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  QSurfaceFormat::setDefaultFormat(format);

  QApplication app(argc, argv);
  QApplication::setOrganizationName("Drape");
  QApplication::setApplicationName("Drape");
  QApplication::setApplicationVersion(DRAPE_VERSION);
  if (QStyle* fusion = QStyleFactory::create("Fusion")) QApplication::setStyle(fusion);

  qt::MainWindow window;
  // --avatar, --fabric and --set apply to the first scene; --set also to every file opened later.
  std::vector<std::pair<std::string, std::string>> base = options.scene.overrides;
  window.document()->setBaseOverrides(base);
  const std::filesystem::path scene =
      options.scene.input.empty() ? assetsDir() / "scenes" / "default.json" : options.scene.input;
  window.show();
  QTimer::singleShot(0, &window, [&window, scene, &options] {
    qt::SceneState state;
    state.input = scene;
    state.avatarFile = options.scene.avatarFile;
    state.avatarUnits = options.scene.avatarUnits;
    for (const auto& [key, value] : options.scene.overrides) state.overrides[key] = value;
    if (!options.scene.fabricPreset.empty()) state.overrides["fabric.preset"] = options.scene.fabricPreset;
    window.document()->change(state, QObject::tr("Open %1").arg(QString::fromStdString(scene.filename().string())));
  });
  return app.exec();
}
#else
int runGui(int argc, char** argv, const CliOptions& options) {
  // Built with -DDRAPE_BUILD_GUI=OFF: only the headless modes exist.
  std::cerr << "drape: this build has no desktop application (configured with DRAPE_BUILD_GUI=OFF); headless modes:\n\n"
            << usageText();
  return 2;
}
#endif

}  // namespace drape::app
