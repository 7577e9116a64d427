#pragma once
// The main window of the desktop application: the viewport in the centre; docks Scene, Fabric, Simulation,
// Statistics and Log; the File, Edit, View and Simulation menus. It owns the document (files, edits, undo)
// and the simulation controller (worker thread); it never steps the simulation itself.
#include <QMainWindow>
#include <filesystem>
#include <memory>

#include "drape/qt/simulation_panel.h"
#include "drape/qt/simulation_worker.h"
#include "drape/sim/snapshot.h"

class QAction;
class QComboBox;
class QDockWidget;
class QLabel;
class QMenu;
class QPlainTextEdit;

namespace drape::qt {

class FabricPanel;
class PatternPanel;
class PatternSheet;
class SceneDocument;
class ScenePanel;
class SimulationController;
class StatisticsPanel;
class UserDialogs;
class ViewportWidget;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  // dialogs: where errors and questions go (null: QMessageBox); the window does not own it.
  explicit MainWindow(UserDialogs* dialogs = nullptr, QWidget* parent = nullptr);
  ~MainWindow() override;

  // Opens a scene or a bare pattern (.json, or DXF-AAMA .dxf), or an avatar mesh (.obj .glb .gltf .fbx .ply .stl) into the
  // current scene. On error the dialog shows the message and the current scene stays. Returns success.
  bool openFile(const std::filesystem::path& file);
  // Writes the scene file atomically; false (with an error dialog) when it cannot.
  bool saveSceneAs(const std::filesystem::path& file);
  // Exports the current (draped) garment; the format follows the extension (.obj, .glb, .gltf, .ply, .stl).
  bool exportGarment(const std::filesystem::path& file);
  // Lays a fabric print (an image file) on the garment, as cut: each panel carries it in its own pattern frame, the
  // image as wide as its resolution says (PNG pHYs; 96 dpi when unstated); switches the display to print. On a file
  // that cannot be read the dialog names it and nothing changes. Returns success.
  bool showPrint(const std::filesystem::path& image);
  // Writes the current pattern (as edited): .json GarmentCode, .dxf DXF-AAMA, .pdf or .svg at full scale.
  bool savePatternAs(const std::filesystem::path& file);
  // Saves the viewport's current frame as a PNG (atomically).
  bool saveScreenshot(const std::filesystem::path& file);
  // Continues the scene from a garment state exported earlier (.obj; SceneDocument::loadGarmentState). On error
  // the dialog names the file and the current state stays. Returns success.
  bool loadGarmentState(const std::filesystem::path& file);

  SceneDocument* document() const { return m_document; }
  SimulationController* controller() const { return m_controller; }
  ViewportWidget* viewport() const { return m_viewport; }
  PatternSheet* patternSheet() const { return m_sheet; }
  PatternPanel* patternPanel() const { return m_patternPanel; }
  FabricPanel* fabricPanel() const { return m_fabricPanel; }
  ScenePanel* scenePanel() const { return m_scenePanel; }
  SimulationPanel* simulationPanel() const { return m_simulationPanel; }
  StatisticsPanel* statisticsPanel() const { return m_statisticsPanel; }
  QPlainTextEdit* logView() const { return m_log; }
  const SimulationActions& simulationActions() const { return m_sim; }
  QAction* undoAction() const { return m_undo; }
  QAction* redoAction() const { return m_redo; }
  // The latest snapshot shown in the viewport (null before any scene).
  std::shared_ptr<const Snapshot> currentSnapshot() const { return m_snapshot; }

  // Recently opened files, most recent first (QSettings "recentFiles").
  static QStringList recentFiles();

 protected:
  void closeEvent(QCloseEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

 private:
  void createActions();
  void createMenus();
  void createDocks();
  void connectDocument();
  void updateActions();
  void updateTitle();
  void refreshPanels();
  void rememberRecent(const std::filesystem::path& file);
  void rebuildRecentMenu();
  void showError(const QString& title, const QString& text);
  void log(const QString& level, const QString& text);
  bool maybeSave();
  bool save();

  void onOpen();
  void onOpenAvatar();
  void onSaveAs();
  void onExport();
  void onLoadState();
  void onScreenshot();
  void onSavePattern();
  void onShowPrint();
  void connectPatternView();
  void showSelectionIn3d();

  std::unique_ptr<UserDialogs> m_ownDialogs;
  UserDialogs* m_dialogs = nullptr;
  SceneDocument* m_document = nullptr;
  SimulationController* m_controller = nullptr;
  ViewportWidget* m_viewport = nullptr;
  PatternSheet* m_sheet = nullptr;
  PatternPanel* m_patternPanel = nullptr;
  ScenePanel* m_scenePanel = nullptr;
  FabricPanel* m_fabricPanel = nullptr;
  SimulationPanel* m_simulationPanel = nullptr;
  StatisticsPanel* m_statisticsPanel = nullptr;
  QPlainTextEdit* m_log = nullptr;
  QLabel* m_status = nullptr;
  QComboBox* m_displayMode = nullptr;
  QMenu* m_recentMenu = nullptr;
  QMenu* m_viewMenu = nullptr;
  SimulationActions m_sim;
  QAction* m_open = nullptr;
  QAction* m_openAvatar = nullptr;
  QAction* m_save = nullptr;
  QAction* m_saveAs = nullptr;
  QAction* m_export = nullptr;
  QAction* m_loadState = nullptr;
  QAction* m_screenshot = nullptr;
  QAction* m_savePattern = nullptr;
  QAction* m_quit = nullptr;
  QAction* m_undo = nullptr;
  QAction* m_redo = nullptr;
  QAction* m_frameAll = nullptr;
  RunState m_runState = RunState::Empty;
  std::shared_ptr<const Snapshot> m_snapshot;
  QList<QDockWidget*> m_docks;
};

}  // namespace drape::qt
