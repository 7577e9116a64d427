// The simulation worker thread: snapshots and step reports arrive on the UI thread through queued signals,
// the garment moves, pause / cancel / reset / destruction during a step are safe.
#include "drape/qt/simulation_controller.h"

#include <QThread>
#include <chrono>
#include <map>
#include <string>
#include <thread>

#include "gui_test_support.h"

namespace drape::test {
namespace {

struct Recorder {
  std::vector<std::shared_ptr<const Snapshot>> snapshots;
  std::vector<StepReport> reports;
  std::vector<qt::RunState> states;
  std::vector<QString> errors;
  std::vector<QString> infos;
  bool offUiThread = false;  // a signal was delivered on another thread than the UI thread

  void attach(qt::SimulationController& c) {
    QObject::connect(&c, &qt::SimulationController::snapshotReady, [this](std::shared_ptr<const Snapshot> s) {
      offUiThread |= QThread::currentThread() != QCoreApplication::instance()->thread();
      snapshots.push_back(std::move(s));
    });
    QObject::connect(&c, &qt::SimulationController::stepReported, [this](const StepReport& r) {
      offUiThread |= QThread::currentThread() != QCoreApplication::instance()->thread();
      reports.push_back(r);
    });
    QObject::connect(&c, &qt::SimulationController::runStateChanged, [this](qt::RunState s) { states.push_back(s); });
    QObject::connect(&c, &qt::SimulationController::errorOccurred, [this](const QString& e) { errors.push_back(e); });
    QObject::connect(&c, &qt::SimulationController::infoOccurred, [this](const QString& n) { infos.push_back(n); });
  }
};

std::shared_ptr<Simulation> makeSimulation(const std::string& edge = "0.1") {
  qt::SceneState state = coarseState(defaultScene());
  state.overrides["mesh.target_edge_length"] = edge;
  // Without the initial relaxation (h_max / 16, velocities zeroed) a few steps move the cloth visibly.
  state.overrides["solver.newton.relaxation"] = "false";
  return std::make_shared<Simulation>(qt::buildScene(state));
}

double maxDisplacement(const Snapshot& a, const Snapshot& b) {
  return (a.positions - b.positions).rowwise().norm().maxCoeff();
}

class SimulationControllerTest : public ::testing::Test {
 protected:
  void SetUp() override { guiApplication(); }
};

TEST_F(SimulationControllerTest, DrapeStepsOnTheWorkerAndSnapshotsArriveOnTheUiThread) {
  qt::SimulationController controller;
  Recorder rec;
  rec.attach(controller);
  EXPECT_NE(controller.worker()->thread(), QCoreApplication::instance()->thread());

  auto simulation = makeSimulation();
  const int vertices = simulation->garment().vertexCount();
  controller.setSimulation(simulation);
  simulation.reset();  // the worker owns it now
  ASSERT_TRUE(waitUntil([&] { return !rec.snapshots.empty(); }));
  const auto placed = rec.snapshots.front();
  EXPECT_EQ(placed->stage, Stage::Placed);
  EXPECT_EQ(placed->positions.rows(), vertices);
  EXPECT_EQ(controller.runState(), qt::RunState::Ready);

  controller.start();
  ASSERT_TRUE(waitUntil([&] { return rec.reports.size() >= 8; })) << "reports: " << rec.reports.size();
  controller.pause();
  ASSERT_TRUE(waitUntil([&] { return controller.runState() == qt::RunState::Paused; }));
  const size_t reportsAtPause = rec.reports.size();
  QTest::qWait(200);
  EXPECT_EQ(rec.reports.size(), reportsAtPause) << "no steps after pause";

  EXPECT_FALSE(rec.offUiThread);
  for (size_t i = 1; i < rec.reports.size(); ++i) EXPECT_GT(rec.reports[i].time, rec.reports[i - 1].time);
  const auto latest = controller.latestSnapshot();
  ASSERT_TRUE(latest);
  EXPECT_NEAR(latest->time, rec.reports.back().time, 1e-12) << "pause sends the state it stopped at";
  // Gravity pulls the cloth down: every reported step advanced time and the garment moved.
  // Free fall for t seconds drops about g t^2 / 2; the cloth (not yet on the sphere) falls at least a third of it.
  const double t = latest->time;
  EXPECT_GT(maxDisplacement(*latest, *placed), 9.81 * t * t / 6.0) << "t = " << t;
  EXPECT_LT(latest->positions.col(1).mean(), placed->positions.col(1).mean());

  controller.resume();
  ASSERT_TRUE(waitUntil([&] { return rec.reports.size() >= reportsAtPause + 3; }));
  controller.pause();
  ASSERT_TRUE(waitUntil([&] { return controller.runState() == qt::RunState::Paused; }));
}

TEST_F(SimulationControllerTest, CancelMidStepThenResetReturnsToThePlacedGarment) {
  qt::SimulationController controller;
  Recorder rec;
  rec.attach(controller);
  controller.setSimulation(makeSimulation("0.04"));  // slower steps, so cancel lands inside one
  ASSERT_TRUE(waitUntil([&] { return !rec.snapshots.empty(); }));
  const auto placed = rec.snapshots.front();
  controller.start();
  ASSERT_TRUE(waitUntil([&] { return rec.reports.size() >= 2; }));
  controller.cancel();
  ASSERT_TRUE(waitUntil([&] { return controller.runState() == qt::RunState::Cancelled; }, 10000));
  const size_t reportsAtCancel = rec.reports.size();
  QTest::qWait(300);
  EXPECT_LE(rec.reports.size(), reportsAtCancel + 1) << "at most the interrupted step reports after cancel";
  // After a cancel, start (Resume) continues from the kept state: the engine's cancel flag is cleared.
  const double cancelledAt = rec.reports.back().time;
  const size_t reportsBeforeResume = rec.reports.size();
  controller.start();
  ASSERT_TRUE(waitUntil([&] { return rec.reports.size() >= reportsBeforeResume + 2; }));
  controller.pause();
  ASSERT_TRUE(waitUntil([&] { return controller.runState() == qt::RunState::Paused; }));
  for (size_t i = reportsBeforeResume; i < rec.reports.size(); ++i) {
    EXPECT_NE(rec.reports[i].status, StepStatus::Cancelled);
    EXPECT_GT(rec.reports[i].time, cancelledAt) << "continues, does not start over";
  }
  // A start issued before a cancel that lands first does nothing (the cancel wins).
  controller.cancel();
  ASSERT_TRUE(waitUntil([&] { return controller.runState() == qt::RunState::Cancelled; }));
  const size_t afterSecondCancel = rec.reports.size();
  QMetaObject::invokeMethod(controller.worker(), [&] { controller.worker()->start(controller.worker()->cancelGeneration() - 1); },
                            Qt::BlockingQueuedConnection);
  QTest::qWait(200);
  EXPECT_EQ(controller.runState(), qt::RunState::Cancelled);
  EXPECT_EQ(rec.reports.size(), afterSecondCancel);

  const size_t snapshotsBefore = rec.snapshots.size();
  controller.reset();
  ASSERT_TRUE(waitUntil(
      [&] { return controller.runState() == qt::RunState::Ready && rec.snapshots.size() > snapshotsBefore; }));
  const auto reset = rec.snapshots.back();
  EXPECT_EQ(reset->time, 0.0);
  EXPECT_EQ(reset->stage, Stage::Placed);
  EXPECT_LT(maxDisplacement(*reset, *placed), 1e-12);
  controller.start();
  ASSERT_TRUE(waitUntil([&] { return rec.reports.size() >= afterSecondCancel + 3; }));
  EXPECT_TRUE(rec.errors.empty());
}

// Destroying the controller while its worker steps cancels the step and joins the thread: no crash, no error, and a
// hang fails at ctest's timeout.
TEST_F(SimulationControllerTest, DestroyingTheControllerDuringAStepJoinsTheWorker) {
  auto controller = std::make_unique<qt::SimulationController>();
  Recorder rec;
  rec.attach(*controller);
  controller->setSimulation(makeSimulation("0.04"));
  controller->start();
  ASSERT_TRUE(waitUntil([&] { return !rec.reports.empty(); }));
  controller.reset();
  EXPECT_TRUE(rec.errors.empty());
}

TEST_F(SimulationControllerTest, DragCommandsReachTheWorkersSimulation) {
  qt::SimulationController controller;
  Recorder rec;
  rec.attach(controller);
  auto simulation = makeSimulation();
  const int vertex = simulation->garment().vertexCount() / 2;
  const Eigen::Vector3d target = simulation->garment().positions.row(vertex).transpose() + Eigen::Vector3d(0, 0.3, 0);
  auto observed = simulation;  // read on the worker thread only
  auto draggedOnWorker = [&] {
    int dragged = -2;
    QMetaObject::invokeMethod(
        controller.worker(), [&] { dragged = observed->draggedVertex(); }, Qt::BlockingQueuedConnection);
    return dragged;  // queued after the commands sent before, so it sees their effect
  };
  controller.setSimulation(simulation);
  simulation.reset();
  ASSERT_TRUE(waitUntil([&] { return controller.runState() == qt::RunState::Ready; }));
  controller.setDrag(vertex, target);
  EXPECT_EQ(draggedOnWorker(), vertex);
  controller.start();
  ASSERT_TRUE(waitUntil([&] { return rec.reports.size() >= 3; }));
  EXPECT_EQ(draggedOnWorker(), vertex) << "the drag survives the steps";
  controller.setDrag(-1, {});
  EXPECT_EQ(draggedOnWorker(), -1);
  controller.pause();
  ASSERT_TRUE(waitUntil([&] { return controller.runState() == qt::RunState::Paused; }));
}

TEST_F(SimulationControllerTest, ANewSimulationReplacesARunningOne) {
  qt::SimulationController controller;
  Recorder rec;
  rec.attach(controller);
  controller.setSimulation(makeSimulation());
  controller.start();
  ASSERT_TRUE(waitUntil([&] { return rec.reports.size() >= 2; }));
  auto second = makeSimulation("0.2");
  const int vertices = second->garment().vertexCount();
  controller.setSimulation(second);
  second.reset();
  ASSERT_TRUE(waitUntil([&] {
    return controller.runState() == qt::RunState::Ready && controller.latestSnapshot() &&
           controller.latestSnapshot()->positions.rows() == vertices;
  }));
  EXPECT_EQ(controller.latestSnapshot()->time, 0.0);
}

// Runs the default scene with `overrides` until `reports` steps were reported, then pauses.
void runDefaultScene(const std::map<std::string, std::string>& overrides, size_t reports,
                     qt::SimulationController& controller, Recorder& rec) {
  qt::SceneState state;
  state.input = assetsDir() / "scenes" / "default.json";
  for (const auto& [key, value] : overrides) state.overrides[key] = value;
  rec.attach(controller);
  controller.setSimulation(std::make_shared<Simulation>(qt::buildScene(state)));
  ASSERT_TRUE(waitUntil([&] { return !rec.snapshots.empty(); }));
  controller.start();
  ASSERT_TRUE(waitUntil([&] { return rec.reports.size() >= reports; }, 20000));
  controller.pause();
  ASSERT_TRUE(waitUntil([&] { return controller.runState() == qt::RunState::Paused; }, 20000));
}

// A stage that settles says so, and so does the hand-over: the full pipeline's preview, limited to 0.02 s, hands over
// to the drape, which the log tells with the time; a preview alone (the default t-shirt on a coarse mesh) comes to
// rest by the drape's own test, and the log says that too.
TEST_F(SimulationControllerTest, HandOverAndRestAreLoggedAsInformation) {
  {
    qt::SimulationController controller;
    Recorder rec;
    ASSERT_NO_FATAL_FAILURE(runDefaultScene(
        {{"solver.stage", "full"}, {"solver.preview.max_time", "0.02"}, {"mesh.target_edge_length", "0.1"}}, 20,
        controller, rec));
    size_t firstDrape = rec.reports.size();
    for (size_t i = 0; i < rec.reports.size() && firstDrape == rec.reports.size(); ++i)
      if (rec.reports[i].stage == Stage::Drape) firstDrape = i;
    ASSERT_LT(firstDrape, rec.reports.size());
    ASSERT_GT(firstDrape, 0u);
    ASSERT_EQ(rec.infos.size(), 1u);
    EXPECT_TRUE(rec.infos.front().contains("The drape takes over from the preview at t = ")) << rec.infos.front().toStdString();
    EXPECT_TRUE(rec.errors.empty());
  }
  qt::SimulationController controller;
  Recorder rec;
  qt::SceneState state;
  state.input = assetsDir() / "scenes" / "default.json";
  state.overrides = {{"solver.stage", "preview"}, {"mesh.target_edge_length", "0.035"}};
  rec.attach(controller);
  controller.setSimulation(std::make_shared<Simulation>(qt::buildScene(state)));
  ASSERT_TRUE(waitUntil([&] { return !rec.snapshots.empty(); }));
  controller.start();
  ASSERT_TRUE(waitUntil([&] { return controller.runState() == qt::RunState::Finished; }, 120000));
  ASSERT_FALSE(rec.reports.empty());
  EXPECT_TRUE(rec.reports.back().atRest);
  ASSERT_EQ(rec.infos.size(), 1u);
  EXPECT_TRUE(rec.infos.front().contains("The preview is at rest at t = ")) << rec.infos.front().toStdString();
}

TEST_F(SimulationControllerTest, ExplodedGarmentStopsWithWhereItExplodedAndKeepsTheStateBeforeIt) {
  // The default t-shirt that no fabric holds together (the softest stretch the settings admit, no shear or bending
  // stiffness, the most friction, which holds it on the body, 1000 m/s^2, 0.1 s steps): the drape stops Diverged,
  // the error names the triangle and its panel, and the garment shown is the last good state, not the exploded one.
  qt::SceneState state;
  state.input = assetsDir() / "scenes" / "default.json";
  state.overrides = {{"solver.stage", "drape"},       {"fabric.stretch_warp", "1e-3"}, {"fabric.stretch_weft", "1e-3"},
                     {"fabric.shear", "0"},           {"fabric.bend_warp", "0"},       {"fabric.bend_weft", "0"},
                     {"fabric.friction", "5"},
                     {"sim.gravity", "-1000"},        {"solver.newton.h_max", "0.1"},  {"solver.max_sim_time", "0.5"}};
  qt::SimulationController controller;
  Recorder rec;
  rec.attach(controller);
  controller.setSimulation(std::make_shared<Simulation>(qt::buildScene(state)));
  ASSERT_TRUE(waitUntil([&] { return !rec.snapshots.empty(); }));
  controller.start();
  ASSERT_TRUE(waitUntil([&] { return !rec.errors.empty(); }, 60000)) << "reports: " << rec.reports.size();
  ASSERT_EQ(rec.errors.size(), 1u);
  const std::string error = rec.errors.front().toStdString();
  EXPECT_NE(error.find("The drape diverged at t = "), std::string::npos) << error;
  EXPECT_NE(error.find("the garment exploded: triangle "), std::string::npos) << error;
  EXPECT_NE(error.find(" of panel '"), std::string::npos) << error;
  ASSERT_TRUE(waitUntil([&] { return controller.runState() == qt::RunState::Paused; }));
  ASSERT_FALSE(rec.reports.empty());
  EXPECT_EQ(rec.reports.back().status, StepStatus::Diverged);
  EXPECT_GT(rec.reports.back().maxStrain, 100.0);
  const auto shown = controller.latestSnapshot();
  ASSERT_TRUE(shown);
  ASSERT_TRUE(shown->positions.allFinite());
  ASSERT_GT(shown->triangleStrain.size(), 0);
  EXPECT_LE(shown->triangleStrain.maxCoeff(), 100.0);
}

}  // namespace
}  // namespace drape::test
