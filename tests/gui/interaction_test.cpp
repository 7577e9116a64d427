// Issue #7's interaction in the main window under Xvfb: Preview then Drape from the preview state, grabbing
// and dragging a garment vertex in the viewport, Ctrl+click pins (undo, redo, save), edits during a drape that
// restart from the last preview state, and Resume after Cancel.
#include <QAction>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QMouseEvent>
#include <QPlainTextEdit>
#include <QTreeWidget>
#include <QUndoStack>

#include "drape/qt/main_window.h"
#include "drape/qt/scene_panel.h"
#include "drape/qt/simulation_controller.h"
#include "drape/qt/statistics_panel.h"
#include "drape/qt/viewport_picking.h"
#include "drape/qt/viewport_widget.h"
#include "gui_test_support.h"

namespace drape::test {
namespace {

// Everything the controller sends to the UI thread, in order.
struct Trace {
  std::vector<std::shared_ptr<const Snapshot>> snapshots;
  std::vector<StepReport> reports;
};

class InteractionTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!guiHaveDisplay()) GTEST_SKIP() << "no display: run under xvfb-run -a";
    guiApplication();
    // The preview falls freely from its first step: the initial relaxation (solver.newton.relaxation, which the
    // preview shares with the drape) moves the cloth g h^2 per step, too little to see in the few steps these tests
    // take.
    auto overrides = unendingDrapeOverrides();
    overrides.emplace_back("solver.newton.relaxation", "false");
    window = openDefaultWindow(&dialogs, overrides);
    ASSERT_NE(window, nullptr) << "the default scene did not open";
    placed = window->currentSnapshot();
    QObject::connect(controller(), &qt::SimulationController::snapshotReady, window.get(),
                     [this](std::shared_ptr<const Snapshot> s) { trace.snapshots.push_back(std::move(s)); });
    QObject::connect(controller(), &qt::SimulationController::stepReported, window.get(),
                     [this](const StepReport& r) { trace.reports.push_back(r); });
  }
  void TearDown() override {
    if (window) {
      dialogs.answer = qt::UserDialogs::SaveChoice::Discard;
      window->close();
    }
  }
  qt::SimulationController* controller() const { return window->controller(); }
  const qt::SimulationActions& actions() const { return window->simulationActions(); }

  // Waits until the worker stopped in state and the UI holds the snapshot of the last reported step.
  void waitStopped(qt::RunState state) {
    ASSERT_TRUE(waitUntil([&] { return controller()->runState() == state; }))
        << qt::toString(controller()->runState()) << " after " << trace.reports.size() << " reports, last at t = "
        << (trace.reports.empty() ? -1.0 : trace.reports.back().time) << " "
        << (trace.reports.empty() ? "" : toString(trace.reports.back().status));
    ASSERT_TRUE(waitUntil([&] {
      return !trace.reports.empty() && window->currentSnapshot() &&
             window->currentSnapshot()->time == trace.reports.back().time;
    }));
  }
  // Runs the action until `steps` more reports arrived, then pauses and waits for the pause snapshot.
  void runSteps(QAction* action, size_t steps) {
    const size_t before = trace.reports.size();
    ASSERT_TRUE(action->isEnabled()) << action->text().toStdString();
    action->trigger();
    ASSERT_TRUE(waitUntil([&] { return trace.reports.size() >= before + steps; }, 60000));
    actions().pause->trigger();
    waitStopped(qt::RunState::Paused);
  }
  // Runs the action until the simulation finishes (at solver.max_steps: the worker outpaces the UI thread on a
  // coarse preview, so "pause after n reports" could land anywhere).
  void runToFinish(QAction* action) {
    ASSERT_TRUE(action->isEnabled()) << action->text().toStdString();
    const size_t before = trace.reports.size();
    action->trigger();
    ASSERT_TRUE(waitUntil([&] { return trace.reports.size() > before; }, 60000));
    waitStopped(qt::RunState::Finished);
  }
  void setMaxSteps(int steps) {
    ASSERT_TRUE(window->document()->setSetting("solver.max_steps", std::to_string(steps)));
    ASSERT_TRUE(waitUntil([&] { return controller()->runState() != qt::RunState::Running; }));
    QTest::qWait(50);
  }
  // A garment vertex away from the sphere (about 0.42 m from its axis), and the widget pixel a little inside one
  // of its triangles, where a click picks it.
  int vertexNear(const Eigen::Vector3d& offset) const {
    const Eigen::Vector3d centre = placed->positions.colwise().mean().transpose();
    int best = 0;
    (placed->positions.rowwise() - (centre + offset).transpose()).rowwise().squaredNorm().minCoeff(&best);
    return best;
  }
  QPointF pixelOf(int vertex) const {
    const auto p = window->viewport()->widgetPosition(window->currentSnapshot()->positions.row(vertex).transpose());
    EXPECT_TRUE(p);
    return p ? *p + QPointF(0.3, 0.3) : QPointF();
  }

  RecordingDialogs dialogs;
  std::unique_ptr<qt::MainWindow> window;
  std::shared_ptr<const Snapshot> placed;
  Trace trace;
};

TEST_F(InteractionTest, PreviewThenDrapeStartsFromThePreviewState) {
  EXPECT_TRUE(actions().preview->isEnabled());
  EXPECT_EQ(actions().preview->toolTip().indexOf("not available"), -1);
  setMaxSteps(12);
  runToFinish(actions().preview);
  ASSERT_EQ(trace.reports.size(), 12u);
  for (const StepReport& r : trace.reports) EXPECT_EQ(r.stage, Stage::Preview);
  const auto preview = window->currentSnapshot();
  EXPECT_EQ(preview->stage, Stage::Preview);
  ASSERT_GT((preview->positions - placed->positions).rowwise().norm().maxCoeff(), 0.01) << "the preview moved";
  EXPECT_FALSE(actions().preview->isEnabled()) << "the preview finished";
  EXPECT_TRUE(actions().drape->isEnabled());

  const size_t firstDrapeSnapshot = trace.snapshots.size();
  const size_t firstDrapeReport = trace.reports.size();
  runToFinish(actions().drape);
  EXPECT_EQ(trace.reports.size(), firstDrapeReport + 12);
  // The first drape snapshot (a preview snapshot of the paused state may still arrive before it).
  std::shared_ptr<const Snapshot> start;
  for (size_t i = firstDrapeSnapshot; i < trace.snapshots.size() && !start; ++i) {
    if (trace.snapshots[i]->stage == Stage::Drape)
      start = trace.snapshots[i];
    else
      EXPECT_EQ(trace.snapshots[i]->time, preview->time);
  }
  ASSERT_TRUE(start);
  EXPECT_EQ(start->time, preview->time);
  EXPECT_LT((start->positions - preview->positions).cwiseAbs().maxCoeff(), 1e-12)
      << "the drape starts from the preview's positions, not from the placed garment";
  for (size_t i = firstDrapeReport; i < trace.reports.size(); ++i) {
    EXPECT_EQ(trace.reports[i].stage, Stage::Drape);
    EXPECT_GT(trace.reports[i].time, preview->time);
  }
  EXPECT_FALSE(actions().preview->isEnabled()) << "no preview once the drape has started";
  EXPECT_EQ(window->statisticsPanel()->figure("stage"), "drape");
  EXPECT_TRUE(dialogs.errors.empty());
}

TEST_F(InteractionTest, DraggingAVertexPullsItTowardsTheCursorTarget) {
  const int steps = 30;
  ASSERT_TRUE(window->document()->setSetting("solver.max_steps", std::to_string(steps)));
  ASSERT_TRUE(waitUntil([&] { return controller()->runState() == qt::RunState::Ready; }));
  const int vertex = vertexNear({0.3, 0.0, 0.3});

  // Without a drag: the preview for `steps` steps.
  actions().preview->trigger();
  waitStopped(qt::RunState::Finished);
  const Eigen::Vector3d free = window->currentSnapshot()->positions.row(vertex).transpose();

  // With a drag: grab the vertex of the placed garment and move the cursor 80 pixels up.
  actions().reset->trigger();
  ASSERT_TRUE(waitUntil([&] {
    return controller()->runState() == qt::RunState::Ready && window->currentSnapshot()->time == 0.0;
  }));
  qt::ViewportWidget* viewport = window->viewport();
  std::vector<std::pair<int, Eigen::Vector3d>> drags;
  QObject::connect(viewport, &qt::ViewportWidget::dragChanged, window.get(),
                   [&](int v, const Eigen::Vector3d& t) { drags.emplace_back(v, t); });
  const render::Camera cameraBefore = viewport->camera();
  const QPointF press = pixelOf(vertex);
  sendMouse(viewport, QEvent::MouseButtonPress, press, Qt::LeftButton);
  ASSERT_EQ(viewport->grabbedVertex(), vertex);
  const QPointF cursor = press + QPointF(0.0, -80.0);
  sendMouse(viewport, QEvent::MouseMove, press + QPointF(0.0, -40.0), Qt::LeftButton);
  sendMouse(viewport, QEvent::MouseMove, cursor, Qt::LeftButton);
  EXPECT_TRUE(viewport->camera().eye.isApprox(cameraBefore.eye)) << "a grab does not orbit";
  ASSERT_GE(drags.size(), 3u);
  const Eigen::Vector3d start = placed->positions.row(vertex).transpose();
  const Eigen::Vector3d target = drags.back().second;
  EXPECT_EQ(drags.back().first, vertex);
  EXPECT_TRUE(drags.front().second.isApprox(start)) << "the press does not move the vertex";
  // The target is under the cursor, in the plane through the grabbed vertex facing the camera.
  const auto shown = viewport->widgetPosition(target);
  ASSERT_TRUE(shown);
  EXPECT_NEAR(shown->x(), cursor.x(), 1.0);
  EXPECT_NEAR(shown->y(), cursor.y(), 1.0);
  EXPECT_NEAR((target - start).dot(qt::viewDirection(viewport->camera())), 0.0, 1e-9);
  EXPECT_GT(target.y() - start.y(), 0.05) << "80 pixels up is well above the vertex";

  actions().preview->trigger();
  waitStopped(qt::RunState::Finished);
  const Eigen::Vector3d dragged = window->currentSnapshot()->positions.row(vertex).transpose();
  sendMouse(viewport, QEvent::MouseButtonRelease, cursor, Qt::NoButton);
  EXPECT_EQ(viewport->grabbedVertex(), -1);
  EXPECT_EQ(drags.back().first, -1) << "release lets go";

  const Eigen::Vector3d towards = (target - start).normalized();
  EXPECT_LT((dragged - target).norm(), (free - target).norm() - 0.05)
      << "free " << free.transpose() << " dragged " << dragged.transpose() << " target " << target.transpose();
  EXPECT_GT((dragged - start).dot(towards), (free - start).dot(towards) + 0.05);
  EXPECT_TRUE(dialogs.errors.empty());
}

TEST_F(InteractionTest, CtrlClickPinsUndoRedoSaveAndThePinnedVertexStays) {
  setMaxSteps(6);
  runToFinish(actions().preview);
  const auto before = window->currentSnapshot();
  const int vertex = vertexNear({-0.4, 0.0, 0.35});
  const QPointF at = pixelOf(vertex);
  ASSERT_EQ(window->viewport()->garmentVertexAt(at), vertex);
  const size_t snapshotsBefore = trace.snapshots.size();
  sendMouse(window->viewport(), QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::ControlModifier);
  sendMouse(window->viewport(), QEvent::MouseButtonRelease, at, Qt::NoButton, Qt::ControlModifier);
  EXPECT_EQ(window->viewport()->grabbedVertex(), -1) << "ctrl+click does not grab";
  EXPECT_EQ(window->document()->vertexPins(), std::vector<int>{vertex});
  EXPECT_EQ(window->document()->undoStack()->count(), 2);
  EXPECT_EQ(window->document()->undoStack()->text(1), QString("Pin vertex %1").arg(vertex));
  const QTreeWidget* tree = window->scenePanel()->tree();
  EXPECT_EQ(tree->topLevelItem(2)->text(0), "Pins (1)");

  // The simulation continues from the paused state (same time, same positions), not from the placed garment.
  ASSERT_TRUE(waitUntil([&] { return trace.snapshots.size() > snapshotsBefore; }));
  const auto continued = trace.snapshots.back();
  EXPECT_EQ(continued->time, before->time);
  EXPECT_LT((continued->positions - before->positions).cwiseAbs().maxCoeff(), 1e-12);
  ASSERT_TRUE(waitUntil([&] { return controller()->runState() == qt::RunState::Paused; }));
  EXPECT_NE(window->logView()->toPlainText().indexOf("continues from its current state"), -1);

  // The pinned vertex stays where it was pinned while the rest falls.
  runToFinish(actions().resume);  // max_steps more steps of the continued preview
  EXPECT_EQ(trace.reports.back().stage, Stage::Preview);
  const auto after = window->currentSnapshot();
  EXPECT_GT(after->time, before->time);
  EXPECT_LT((after->positions.row(vertex) - before->positions.row(vertex)).norm(), 1e-3);
  double fall = 0.0;
  for (Eigen::Index v = 0; v < after->positions.rows(); ++v)
    if (v != vertex) fall = std::max(fall, before->positions(v, 1) - after->positions(v, 1));
  EXPECT_GT(fall, 0.02) << "the free cloth kept falling";

  // Undo removes the pin, redo adds it back; the Scene dock follows.
  window->undoAction()->trigger();
  EXPECT_TRUE(window->document()->vertexPins().empty());
  EXPECT_EQ(window->scenePanel()->tree()->topLevelItem(2)->text(0), "Pins (0)");
  window->redoAction()->trigger();
  EXPECT_EQ(window->document()->vertexPins(), std::vector<int>{vertex});
  EXPECT_EQ(window->scenePanel()->tree()->topLevelItem(2)->text(0), "Pins (1)");

  // The saved scene holds the pin and loads back with it.
  const std::filesystem::path saved = testOutputDir() / "gui_pinned_scene.json";
  std::filesystem::remove(saved);
  ASSERT_TRUE(window->saveSceneAs(saved));
  QFile file(QString::fromStdString(saved.string()));
  ASSERT_TRUE(file.open(QIODevice::ReadOnly));
  const QJsonObject root = QJsonDocument::fromJson(file.readAll()).object();
  ASSERT_TRUE(root["pins"].isArray());
  const QJsonArray pins = root["pins"].toArray();
  ASSERT_EQ(pins.size(), 1);
  EXPECT_EQ(pins[0].toObject()["vertices"].toArray(), QJsonArray{vertex});
  EXPECT_FALSE(root["solver"].toObject().contains("stage")) << "the stage the simulation runs in is not saved";
  const Scene reloaded = loadScene(coarseState(saved).request());
  ASSERT_EQ(reloaded.pins.size(), 1u);
  EXPECT_EQ(reloaded.pins[0].vertices, std::vector<int>{vertex});

  // A second ctrl+click on the vertex unpins it.
  const QPointF again = pixelOf(vertex);
  sendMouse(window->viewport(), QEvent::MouseButtonPress, again, Qt::LeftButton, Qt::ControlModifier);
  sendMouse(window->viewport(), QEvent::MouseButtonRelease, again, Qt::NoButton, Qt::ControlModifier);
  EXPECT_TRUE(window->document()->vertexPins().empty());
  EXPECT_EQ(window->document()->undoStack()->text(2), QString("Unpin vertex %1").arg(vertex));
  EXPECT_TRUE(dialogs.errors.empty());
}

TEST_F(InteractionTest, FabricChangeDuringADrapeRestartsFromTheLastPreviewState) {
  setMaxSteps(10);
  runToFinish(actions().preview);
  const auto preview = window->currentSnapshot();
  ASSERT_GT((preview->positions - placed->positions).rowwise().norm().maxCoeff(), 0.01);
  // A long drape: lifting the step limit continues the finished preview where it is (a continued edit). Without
  // the scene's time limit and the early stop the drape also runs until the pause below: on a loaded machine the
  // worker could otherwise finish the drape before the UI thread pauses it.
  ASSERT_TRUE(window->document()->setSettings({{"solver.max_steps", "100000"},
                                               {"solver.max_sim_time", "1000"},
                                               {"solver.newton.rest_speed", "0"}},
                                              "Long drape"));
  ASSERT_TRUE(waitUntil([&] { return controller()->runState() != qt::RunState::Running; }));
  ASSERT_TRUE(waitUntil([&] { return controller()->runState() == qt::RunState::Paused; }));
  ASSERT_TRUE(waitUntil([&] { return window->currentSnapshot() != preview; }));
  EXPECT_EQ(window->currentSnapshot()->time, preview->time);
  EXPECT_LT((window->currentSnapshot()->positions - preview->positions).cwiseAbs().maxCoeff(), 1e-12);
  actions().drape->trigger();
  ASSERT_TRUE(waitUntil([&] { return !trace.reports.empty() && trace.reports.back().stage == Stage::Drape; }, 60000));
  ASSERT_TRUE(waitUntil([&] { return trace.reports.back().time > preview->time + 0.002; }, 60000));
  ASSERT_EQ(controller()->runState(), qt::RunState::Running);

  const size_t snapshotsBefore = trace.snapshots.size();
  ASSERT_TRUE(window->document()->setFabricPreset("denim"));
  EXPECT_EQ(window->document()->scene().fabric.stretchWarp, loadFabricPreset("denim").stretchWarp);
  EXPECT_EQ(window->document()->scene().settings.text("solver.stage"), "drape") << "the document keeps its stage";
  // The new simulation's first snapshot: the preview's final state, not the placed garment nor the drape's.
  std::shared_ptr<const Snapshot> first;
  ASSERT_TRUE(waitUntil([&] {
    for (size_t i = snapshotsBefore; i < trace.snapshots.size() && !first; ++i)
      if (trace.snapshots[i]->time == preview->time) first = trace.snapshots[i];
    return first != nullptr;
  }));
  EXPECT_EQ(first->stage, Stage::Drape);
  EXPECT_LT((first->positions - preview->positions).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT((first->positions - placed->positions).cwiseAbs().maxCoeff(), 0.01);
  // It keeps running without a click: more drape steps after the restart.
  const size_t reportsNow = trace.reports.size();
  ASSERT_TRUE(waitUntil([&] { return trace.reports.size() >= reportsNow + 3; }, 60000));
  EXPECT_EQ(trace.reports.back().stage, Stage::Drape);
  actions().pause->trigger();
  waitStopped(qt::RunState::Paused);

  // Undo (back to cotton) restarts from the same preview state too.
  const size_t beforeUndo = trace.snapshots.size();
  window->undoAction()->trigger();
  std::shared_ptr<const Snapshot> undone;
  ASSERT_TRUE(waitUntil([&] {
    for (size_t i = beforeUndo; i < trace.snapshots.size() && !undone; ++i)
      if (trace.snapshots[i]->time == preview->time) undone = trace.snapshots[i];
    return undone != nullptr;
  }));
  EXPECT_LT((undone->positions - preview->positions).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_TRUE(dialogs.errors.empty());
}

TEST_F(InteractionTest, ResumeAndDrapeContinueAfterCancel) {
  // A finer mesh makes steps long enough to cancel inside one.
  ASSERT_TRUE(window->document()->setSetting("mesh.target_edge_length", "0.04"));
  ASSERT_TRUE(waitUntil([&] { return controller()->runState() == qt::RunState::Ready; }));
  actions().drape->trigger();
  ASSERT_TRUE(waitUntil([&] { return trace.reports.size() >= 2; }, 60000));
  actions().cancel->trigger();
  waitStopped(qt::RunState::Cancelled);
  const auto cancelled = window->currentSnapshot();
  EXPECT_GT(cancelled->time, 0.0);
  EXPECT_TRUE(actions().resume->isEnabled());
  EXPECT_TRUE(actions().drape->isEnabled());

  const size_t reports = trace.reports.size();
  runSteps(actions().resume, 2);
  for (size_t i = reports; i < trace.reports.size(); ++i) {
    EXPECT_NE(trace.reports[i].status, StepStatus::Cancelled);
    EXPECT_GT(trace.reports[i].time, cancelled->time) << "continues from the kept state, not from the start";
  }
  actions().cancel->setEnabled(true);  // Paused: cancel directly
  controller()->cancel();
  ASSERT_TRUE(waitUntil([&] { return controller()->runState() == qt::RunState::Cancelled; }));
  const double stoppedAt = trace.reports.back().time;
  const size_t more = trace.reports.size();
  runSteps(actions().drape, 2);
  EXPECT_GT(trace.reports[more].time, stoppedAt);
  EXPECT_EQ(trace.reports[more].stage, Stage::Drape);
  EXPECT_TRUE(dialogs.errors.empty());
}

}  // namespace
}  // namespace drape::test
