#include "drape/qt/main_window.h"

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QDateTime>
#include <QDockWidget>
#include <QKeySequence>
#include <QLabel>
#include <QMenuBar>
#include <QPlainTextEdit>
#include <QScreen>
#include <QScrollArea>
#include <QScrollBar>
#include <QSplitter>
#include <QUndoCommand>
#include <QStatusBar>
#include <QStyle>
#include <QToolBar>
#include <QUndoStack>

#include "drape/qt/fabric_panel.h"
#include "drape/qt/pattern_sheet.h"
#include "drape/qt/pattern_view.h"
#include "drape/qt/scene_document.h"
#include "drape/qt/scene_panel.h"
#include "drape/qt/simulation_controller.h"
#include "drape/qt/speed_accuracy.h"
#include "drape/qt/statistics_panel.h"
#include "drape/qt/user_dialogs.h"
#include "drape/qt/viewport_widget.h"
#include "drape/render/camera.h"

namespace drape::qt {

MainWindow::MainWindow(UserDialogs* dialogs, QWidget* parent) : QMainWindow(parent) {
  if (!dialogs) {
    m_ownDialogs = std::make_unique<UserDialogs>();
    dialogs = m_ownDialogs.get();
  }
  m_dialogs = dialogs;
  setObjectName("DrapeMainWindow");
  setAcceptDrops(true);
  setDockOptions(QMainWindow::AnimatedDocks | QMainWindow::AllowTabbedDocks);
  m_document = new SceneDocument(this);
  m_controller = new SimulationController(this);
  m_viewport = new ViewportWidget;
  m_viewport->setMinimumSize(320, 240);
  // The flat pattern beside the drape.
  m_sheet = new PatternSheet(this);
  m_patternPanel = new PatternPanel(m_sheet);
  auto* centre = new QSplitter(Qt::Horizontal);
  centre->setObjectName("CentreSplitter");
  centre->addWidget(m_viewport);
  centre->addWidget(m_patternPanel);
  centre->setStretchFactor(0, 3);
  centre->setStretchFactor(1, 2);
  centre->setSizes({600, 400});
  centre->setChildrenCollapsible(false);
  setCentralWidget(centre);
  createActions();
  createDocks();
  createMenus();
  connectDocument();
  connectPatternView();
  m_status = new QLabel;
  statusBar()->addPermanentWidget(m_status);
  updateActions();
  updateTitle();
  // 1440 x 900, or what the screen holds.
  QSize size(1440, 900);
  if (const QScreen* s = screen()) size = size.boundedTo(s->availableGeometry().size());
  resize(size);
}

MainWindow::~MainWindow() {
  // Joins the worker thread (cancelling a step in progress) before the panels it reports to go away.
  delete m_controller;
  m_controller = nullptr;
  // The document is a child that would go after this destructor, and its undo stack signals while it goes: those
  // signals must not reach this half-destroyed window.
  m_document->undoStack()->disconnect(this);
  m_document->disconnect(this);
  delete m_document;
  m_document = nullptr;
}

void MainWindow::createActions() {
  QStyle* s = style();
  m_open = new QAction(s->standardIcon(QStyle::SP_DialogOpenButton), tr("&Open Scene or Pattern..."), this);
  m_open->setShortcut(QKeySequence::Open);
  connect(m_open, &QAction::triggered, this, &MainWindow::onOpen);
  m_openAvatar = new QAction(tr("Open &Avatar..."), this);
  m_openAvatar->setShortcut(QKeySequence(tr("Ctrl+Shift+O")));
  connect(m_openAvatar, &QAction::triggered, this, &MainWindow::onOpenAvatar);
  m_save = new QAction(s->standardIcon(QStyle::SP_DialogSaveButton), tr("&Save Scene"), this);
  m_save->setShortcut(QKeySequence::Save);
  connect(m_save, &QAction::triggered, this, [this] { save(); });
  m_saveAs = new QAction(tr("Save Scene &As..."), this);
  m_saveAs->setShortcut(QKeySequence::SaveAs);
  connect(m_saveAs, &QAction::triggered, this, &MainWindow::onSaveAs);
  m_export = new QAction(tr("&Export Draped Garment..."), this);
  m_export->setShortcut(QKeySequence(tr("Ctrl+E")));
  connect(m_export, &QAction::triggered, this, &MainWindow::onExport);
  m_loadState = new QAction(tr("&Load Garment State..."), this);
  m_loadState->setToolTip(tr("Continue from a garment exported earlier as OBJ for this scene"));
  connect(m_loadState, &QAction::triggered, this, &MainWindow::onLoadState);
  m_screenshot = new QAction(tr("Save Screens&hot..."), this);
  m_screenshot->setShortcut(QKeySequence(tr("Ctrl+Alt+S")));
  connect(m_screenshot, &QAction::triggered, this, &MainWindow::onScreenshot);
  m_savePattern = new QAction(tr("Save &Pattern As..."), this);
  m_savePattern->setToolTip(tr("Write the pattern as edited: GarmentCode JSON, DXF-AAMA, or PDF and SVG at full scale"));
  connect(m_savePattern, &QAction::triggered, this, &MainWindow::onSavePattern);
  m_quit = new QAction(tr("&Quit"), this);
  m_quit->setShortcut(QKeySequence::Quit);
  connect(m_quit, &QAction::triggered, this, &QWidget::close);

  m_undo = m_document->undoStack()->createUndoAction(this, tr("&Undo"));
  m_undo->setShortcut(QKeySequence::Undo);
  m_redo = m_document->undoStack()->createRedoAction(this, tr("&Redo"));
  m_redo->setShortcut(QKeySequence::Redo);

  m_sim.preview = new QAction(s->standardIcon(QStyle::SP_MediaSeekForward), tr("Pre&view"), this);
  m_sim.preview->setShortcut(QKeySequence(Qt::SHIFT | Qt::Key_F5));
  m_sim.preview->setToolTip(
      tr("Run the fast preview (the drape's own model by L-BFGS on pd-dd's domain-decomposed system) from the placed "
         "garment; drag vertices "
         "with the mouse and Ctrl+click to pin while it runs (Shift+F5)"));
  m_sim.preview->setStatusTip(m_sim.preview->toolTip());
  connect(m_sim.preview, &QAction::triggered, m_controller, &SimulationController::preview);
  m_sim.drape = new QAction(s->standardIcon(QStyle::SP_MediaPlay), tr("&Drape"), this);
  m_sim.drape->setShortcut(QKeySequence(Qt::Key_F5));
  m_sim.drape->setToolTip(
      tr("Run the accurate drape (Backward-Euler Newton) until the garment rests, starting from the preview "
         "state when a preview has run (F5)"));
  m_sim.drape->setStatusTip(m_sim.drape->toolTip());
  connect(m_sim.drape, &QAction::triggered, m_controller, &SimulationController::drape);
  m_sim.pause = new QAction(s->standardIcon(QStyle::SP_MediaPause), tr("&Pause"), this);
  m_sim.pause->setShortcut(QKeySequence(Qt::Key_F6));
  connect(m_sim.pause, &QAction::triggered, m_controller, &SimulationController::pause);
  m_sim.resume = new QAction(s->standardIcon(QStyle::SP_MediaSeekForward), tr("Res&ume"), this);
  m_sim.resume->setShortcut(QKeySequence(Qt::Key_F7));
  connect(m_sim.resume, &QAction::triggered, m_controller, &SimulationController::resume);
  m_sim.reset = new QAction(s->standardIcon(QStyle::SP_MediaSkipBackward), tr("R&eset"), this);
  m_sim.reset->setShortcut(QKeySequence(tr("Ctrl+R")));
  m_sim.reset->setToolTip(tr("Back to the placed garment (Ctrl+R)"));
  connect(m_sim.reset, &QAction::triggered, m_controller, &SimulationController::reset);
  m_sim.cancel = new QAction(s->standardIcon(QStyle::SP_MediaStop), tr("&Cancel"), this);
  m_sim.cancel->setShortcut(QKeySequence(Qt::Key_Escape));
  m_sim.cancel->setToolTip(tr("Interrupt the current step and stop; Resume or Drape continue, Reset starts again (Esc)"));
  connect(m_sim.cancel, &QAction::triggered, m_controller, &SimulationController::cancel);

  m_frameAll = new QAction(tr("&Frame All"), this);
  m_frameAll->setShortcut(QKeySequence(Qt::Key_F));
  connect(m_frameAll, &QAction::triggered, m_viewport, &ViewportWidget::frameAll);
}

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(m_open);
  file->addAction(m_openAvatar);
  m_recentMenu = file->addMenu(tr("Open &Recent"));
  file->addSeparator();
  file->addAction(m_save);
  file->addAction(m_saveAs);
  file->addAction(m_savePattern);
  file->addSeparator();
  file->addAction(m_export);
  file->addAction(m_loadState);
  file->addAction(m_screenshot);
  file->addSeparator();
  file->addAction(m_quit);
  rebuildRecentMenu();

  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  edit->addAction(m_undo);
  edit->addAction(m_redo);

  m_viewMenu = menuBar()->addMenu(tr("&View"));
  int key = Qt::Key_1;
  for (render::ViewPreset preset : render::kAllViewPresets) {
    QString name = QString::fromUtf8(render::viewPresetName(preset).data(), render::viewPresetName(preset).size());
    name[0] = name[0].toUpper();
    auto* action = m_viewMenu->addAction(name);
    action->setShortcut(QKeySequence(key++));
    connect(action, &QAction::triggered, this, [this, preset] { m_viewport->setViewPreset(preset); });
  }
  m_viewMenu->addAction(m_frameAll);
  m_viewMenu->addAction(tr("Fabric &Print..."), this, &MainWindow::onShowPrint);
  m_viewMenu->addSeparator();

  QMenu* simulation = menuBar()->addMenu(tr("&Simulation"));
  for (QAction* a : {m_sim.preview, m_sim.drape, m_sim.pause, m_sim.resume, m_sim.reset, m_sim.cancel})
    simulation->addAction(a);

  QToolBar* bar = addToolBar(tr("Main"));
  bar->setObjectName("MainToolBar");
  bar->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  bar->addAction(m_open);
  bar->addAction(m_save);
  bar->addSeparator();
  for (QAction* a : {m_sim.preview, m_sim.drape, m_sim.pause, m_sim.resume, m_sim.reset}) bar->addAction(a);
  bar->addSeparator();
  bar->addWidget(new QLabel(tr(" Display ")));
  m_displayMode = new QComboBox;
  for (auto mode : {render::DisplayMode::Shaded, render::DisplayMode::Wireframe, render::DisplayMode::Strain,
                    render::DisplayMode::Domains, render::DisplayMode::Contacts, render::DisplayMode::Print}) {
    const auto name = render::displayModeName(mode);
    m_displayMode->addItem(QString::fromUtf8(name.data(), name.size()), static_cast<int>(mode));
  }
  m_displayMode->setToolTip(
      tr("Display mode: shaded, wireframe, strain map, solver domains, contacts, the fabric's print (View > Fabric "
         "Print...)"));
  bar->addWidget(m_displayMode);
  connect(m_displayMode, &QComboBox::activated, this, [this](int index) {
    render::RenderOptions options = m_viewport->renderOptions();
    options.mode = static_cast<render::DisplayMode>(m_displayMode->itemData(index).toInt());
    m_viewport->setRenderOptions(options);
  });
  auto* overlay = bar->addAction(tr("Edges"));
  overlay->setCheckable(true);
  overlay->setToolTip(tr("Draw the triangle edges over any display mode"));
  connect(overlay, &QAction::toggled, this, [this](bool on) {
    render::RenderOptions options = m_viewport->renderOptions();
    options.wireframeOverlay = on;
    m_viewport->setRenderOptions(options);
  });
  bar->addAction(m_frameAll);
}

void MainWindow::createDocks() {
  auto dock = [this](const QString& title, const char* name, QWidget* widget, Qt::DockWidgetArea area) {
    auto* d = new QDockWidget(title, this);
    d->setObjectName(name);
    d->setWidget(widget);
    addDockWidget(area, d);
    return d;
  };
  // A panel scrolls up and down when its dock is shorter than the panel (a laptop's 768 pixels hold the docks of one
  // side only so), never sideways: the dock is at least as wide as the panel needs.
  auto scrolled = [](QWidget* panel) {
    auto* area = new QScrollArea;
    area->setWidget(panel);
    area->setWidgetResizable(true);
    area->setFrameShape(QFrame::NoFrame);
    area->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    area->setMinimumWidth(panel->minimumSizeHint().width() + area->verticalScrollBar()->sizeHint().width());
    return area;
  };
  m_scenePanel = new ScenePanel;
  m_fabricPanel = new FabricPanel;
  m_simulationPanel = new SimulationPanel(m_sim);
  m_statisticsPanel = new StatisticsPanel;
  m_log = new QPlainTextEdit;
  m_log->setReadOnly(true);
  m_log->setMaximumBlockCount(5000);
  QDockWidget* sceneDock = dock(tr("Scene"), "SceneDock", scrolled(m_scenePanel), Qt::LeftDockWidgetArea);
  QDockWidget* fabricDock = dock(tr("Fabric"), "FabricDock", scrolled(m_fabricPanel), Qt::LeftDockWidgetArea);
  QDockWidget* simDock =
      dock(tr("Simulation"), "SimulationDock", scrolled(m_simulationPanel), Qt::RightDockWidgetArea);
  QDockWidget* statsDock =
      dock(tr("Statistics"), "StatisticsDock", scrolled(m_statisticsPanel), Qt::RightDockWidgetArea);
  QDockWidget* logDock = dock(tr("Log"), "LogDock", m_log, Qt::BottomDockWidgetArea);
  resizeDocks({sceneDock, fabricDock}, {330, 330}, Qt::Horizontal);
  resizeDocks({simDock, statsDock}, {360, 360}, Qt::Horizontal);
  resizeDocks({logDock}, {110}, Qt::Vertical);
  m_docks = {sceneDock, fabricDock, simDock, statsDock, logDock};
  if (!m_simulationPanel->levelsError().isEmpty())
    log(tr("error"), tr("The speed/accuracy slider is disabled: %1 (written by %2)")
                         .arg(m_simulationPanel->levelsError(),
                              QString::fromUtf8(trade::kLevelsCommand.data(), trade::kLevelsCommand.size())));

  connect(m_fabricPanel, &FabricPanel::presetChosen, this, [this](const std::string& preset) {
    if (!m_document->setFabricPreset(preset)) refreshPanels();
  });
  connect(m_fabricPanel, &FabricPanel::parameterEdited, this, [this](const std::string& key, const std::string& value) {
    if (!m_document->setSetting(key, value)) refreshPanels();
  });
  connect(m_scenePanel, &ScenePanel::panelFabricChosen, this,
          [this](const std::string& panel, const std::string& preset) {
            if (!m_document->setPanelFabric(panel, preset)) refreshPanels();
          });
  connect(m_scenePanel, &ScenePanel::openAvatarRequested, this, &MainWindow::onOpenAvatar);
  connect(m_scenePanel, &ScenePanel::avatarUnitsChosen, this, [this](const std::string& units) {
    if (!m_document->setSetting("avatar.units", units)) refreshPanels();
  });
  connect(m_simulationPanel, &SimulationPanel::speedAccuracyChosen, this, [this](int level) {
    const SpeedAccuracyLevel& l = speedAccuracyLevels().at(level);
    if (!m_document->setSettings(l.settings, tr("Speed/accuracy: %1").arg(QString::fromStdString(l.name))))
      refreshPanels();
  });
  connect(m_simulationPanel, &SimulationPanel::settingEdited, this,
          [this](const std::string& key, const std::string& value) {
            if (!m_document->setSetting(key, value)) refreshPanels();
          });
}

void MainWindow::connectDocument() {
  connect(m_document, &SceneDocument::sceneChanged, this, [this](std::shared_ptr<Simulation> simulation) {
    QStringList terms;
    for (const auto& t : simulation->terms()) terms << QString::fromStdString(t);
    log(tr("info"), tr("Scene %1: %2 vertices, %3 triangles, %4 pinned; solver terms: %5")
                        .arg(QString::fromStdString(m_document->state().input.filename().string()))
                        .arg(simulation->garment().vertexCount())
                        .arg(simulation->garment().triangleCount())
                        .arg(simulation->pinned().size())
                        .arg(terms.join(", ")));
    if (simulation->resumed()) {
      // An edit of the running scene (fabric, pin, setting): continue from the current state.
      log(tr("info"), tr("The %1 continues from %2 (t = %3 s)")
                          .arg(stageName(simulation->stage()))
                          .arg(simulation->stage() == Stage::Drape ? tr("the last preview state") : tr("its current state"))
                          .arg(simulation->time(), 0, 'f', 3));
      m_controller->continueWith(std::move(simulation));
    } else {
      m_controller->setSimulation(std::move(simulation));
      m_statisticsPanel->clear();
    }
    refreshPanels();
    updateTitle();
  });
  m_document->setResumeSource([this] {
    return m_controller ? m_controller->latestResumeState() : std::optional<ResumeState>();
  });
  m_viewport->setGarmentInteraction(true);
  connect(m_viewport, &ViewportWidget::dragChanged, this, [this](int vertex, const Eigen::Vector3d& target) {
    m_controller->setDrag(vertex, target);
  });
  connect(m_viewport, &ViewportWidget::pinToggleRequested, this, [this](int vertex) { m_document->togglePin(vertex); });
  connect(m_controller, &SimulationController::stageChanged, this, [this] { updateActions(); });
  connect(m_document, &SceneDocument::errorOccurred, this,
          [this](const QString& message) { showError(tr("Cannot use this input"), message); });
  connect(m_document, &SceneDocument::warningsReported, this, [this](const QStringList& warnings) {
    for (const QString& w : warnings) log(tr("warning"), w);
  });
  connect(m_document->undoStack(), &QUndoStack::cleanChanged, this, [this] { updateTitle(); });
  connect(m_controller, &SimulationController::snapshotReady, this, [this](std::shared_ptr<const Snapshot> s) {
    m_snapshot = std::move(s);
    m_viewport->setSnapshot(*m_snapshot);
    m_statisticsPanel->setStage(stageName(m_snapshot->stage));
    m_status->setText(tr("%1 | t = %2 s | %3 vertices, %4 triangles")
                          .arg(QString::fromUtf8(toString(m_runState)))
                          .arg(m_snapshot->time, 0, 'f', 3)
                          .arg(m_snapshot->positions.rows())
                          .arg(m_snapshot->triangles.rows()));
  });
  connect(m_controller, &SimulationController::stepReported, m_statisticsPanel, &StatisticsPanel::addReport);
  connect(m_controller, &SimulationController::runStateChanged, this, [this](RunState state) {
    m_runState = state;
    if (state == RunState::Ready) m_statisticsPanel->clear();
    if (state == RunState::Running) m_statisticsPanel->clearQuality();  // a verdict belongs to a finished stage
    const QString what = m_controller->stage() == Stage::Preview ? tr("Preview") : tr("Drape");
    if (state == RunState::Finished) log(tr("info"), tr("%1 finished").arg(what));
    if (state == RunState::Cancelled) log(tr("info"), tr("%1 cancelled; Resume continues, Reset starts again").arg(what));
    updateActions();
  });
  connect(m_controller, &SimulationController::errorOccurred, this,
          [this](const QString& message) { showError(tr("Simulation"), message); });
  connect(m_controller, &SimulationController::infoOccurred, this,
          [this](const QString& message) { log(tr("info"), message); });
  connect(m_controller, &SimulationController::qualityReported, this, [this](const QualityReport& report) {
    m_statisticsPanel->setQuality(report);
    for (const QualityCheck& c : report.checks)
      if (!c.passed) log(tr("warning"), tr("quality: %1").arg(QString::fromStdString(c.message)));
    if (report.passed) log(tr("info"), tr("Quality: every check passed"));
  });
}

void MainWindow::updateActions() {
  const bool scene = m_document->hasScene();
  const RunState s = m_runState;
  const Stage stage = m_controller ? m_controller->stage() : Stage::Placed;
  const bool idle = s != RunState::Empty && s != RunState::Running;
  // Preview: from the placed garment, or continuing a preview; Drape: from the placed garment, from the preview
  // state, or continuing a drape that has not finished.
  m_sim.preview->setEnabled(idle &&
                            (stage == Stage::Placed || (stage == Stage::Preview && s != RunState::Finished)));
  m_sim.drape->setEnabled(idle && !(stage == Stage::Drape && s == RunState::Finished));
  m_sim.pause->setEnabled(s == RunState::Running);
  m_sim.resume->setEnabled(s == RunState::Paused || s == RunState::Cancelled);
  m_sim.cancel->setEnabled(s == RunState::Running);
  m_sim.reset->setEnabled(s != RunState::Empty && s != RunState::Ready);
  m_save->setEnabled(scene);
  m_saveAs->setEnabled(scene);
  m_export->setEnabled(scene);
  m_loadState->setEnabled(scene);
  m_screenshot->setEnabled(scene);
  m_savePattern->setEnabled(scene);
  m_openAvatar->setEnabled(scene);
}

void MainWindow::updateTitle() {
  setWindowTitle(tr("%1[*] - Drape").arg(m_document->displayName()));
  setWindowModified(m_document->isModified());
}

void MainWindow::refreshPanels() {
  if (!m_document->hasScene()) return;
  const Scene& scene = m_document->scene();
  m_scenePanel->showScene(scene, m_document->state().panelPresets, m_document->heldVerticesPerPin());
  m_fabricPanel->showFabric(scene.fabric, scene.settings.text("fabric.preset"));
  m_simulationPanel->showSettings(scene.settings);
  updateActions();
}

void MainWindow::showError(const QString& title, const QString& text) {
  log(tr("error"), text);
  m_dialogs->showError(this, title, text);
}

void MainWindow::log(const QString& level, const QString& text) {
  const QString time = QDateTime::currentDateTime().toString("HH:mm:ss");
  const QString color = level == tr("error") ? "#c0392b" : level == tr("warning") ? "#b9770e" : "#555555";
  m_log->appendHtml(
      QStringLiteral("<span style='color:%1'>%2 [%3] %4</span>").arg(color, time, level, text.toHtmlEscaped()));
}

}  // namespace drape::qt
