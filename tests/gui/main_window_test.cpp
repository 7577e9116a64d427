// The main window under Xvfb: open a scene, drape it on the worker from the Drape action, edit and undo a
// fabric through the dock, bad files end in the error dialog with the scene intact, every setting is listed,
// export and screenshots are written, unsaved changes prompt on close.
#include "drape/qt/main_window.h"

#include <QAction>
#include <QComboBox>
#include <QImage>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QSlider>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "drape/core/input_error.h"
#include "drape/io/mesh_export.h"
#include "drape/qt/fabric_panel.h"
#include "drape/qt/scene_panel.h"
#include "drape/qt/settings_table.h"
#include "drape/qt/simulation_controller.h"
#include "drape/qt/speed_accuracy.h"
#include "drape/qt/statistics_panel.h"
#include "drape/qt/viewport_widget.h"
#include "gui_test_support.h"
#include "scaled_obj.h"

namespace drape::test {
namespace {

class MainWindowTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!guiHaveDisplay()) GTEST_SKIP() << "no display: run under xvfb-run -a";
    guiApplication();
    window = openDefaultWindow(&dialogs, unendingDrapeOverrides());
    ASSERT_NE(window, nullptr) << "the default scene did not open";
  }
  void TearDown() override {
    if (window) {
      dialogs.answer = qt::UserDialogs::SaveChoice::Discard;
      window->close();
    }
  }
  void drapeSteps(int steps) {
    window->simulationActions().drape->trigger();
    ASSERT_TRUE(waitUntil([&] { return window->statisticsPanel()->steps() >= steps; }));
    window->simulationActions().pause->trigger();
    ASSERT_TRUE(waitUntil([&] { return window->controller()->runState() == qt::RunState::Paused; }));
    QTest::qWait(50);  // the pause snapshot
  }
  RecordingDialogs dialogs;
  std::unique_ptr<qt::MainWindow> window;
};

TEST_F(MainWindowTest, DrapeActionRunsOnTheWorkerAndTheViewportFollows) {
  const auto placed = window->currentSnapshot();
  EXPECT_EQ(window->viewport()->snapshot().positions.rows(), placed->positions.rows());
  EXPECT_TRUE(window->simulationActions().drape->isEnabled());
  EXPECT_FALSE(window->simulationActions().pause->isEnabled());
  drapeSteps(5);
  const auto draped = window->currentSnapshot();
  ASSERT_NE(draped, placed);
  EXPECT_GT(draped->time, 0.0);
  EXPECT_GT((draped->positions - placed->positions).rowwise().norm().maxCoeff(), 1e-6);
  EXPECT_TRUE(draped->positions.isApprox(window->viewport()->snapshot().positions));
  EXPECT_NE(window->statisticsPanel()->figure("iterations"), "-");
  // Equilibrium: the unbalanced force and the last step's largest displacement.
  EXPECT_NE(window->statisticsPanel()->figure("unbalanced force").indexOf("% RMS"), -1)
      << window->statisticsPanel()->figure("unbalanced force").toStdString();
  EXPECT_NE(window->statisticsPanel()->figure("last step moved").indexOf(" mm"), -1);
  EXPECT_GT(window->statisticsPanel()->plottedPoints(), 0)
      << "residual " << window->statisticsPanel()->figure("residual").toStdString() << " steps "
      << window->statisticsPanel()->steps();
  EXPECT_TRUE(window->simulationActions().resume->isEnabled());
  EXPECT_TRUE(window->simulationActions().reset->isEnabled());
  // The viewport draws the garment: the frame is not one flat colour.
  const QImage frame = window->viewport()->grabFramebuffer();
  ASSERT_FALSE(frame.isNull());
  EXPECT_TRUE(window->viewport()->lastError().isEmpty()) << window->viewport()->lastError().toStdString();
  std::set<QRgb> colours;
  for (int y = 0; y < frame.height(); y += 7)
    for (int x = 0; x < frame.width(); x += 7) colours.insert(frame.pixel(x, y));
  EXPECT_GT(colours.size(), 50u);

  window->simulationActions().reset->trigger();
  ASSERT_TRUE(waitUntil([&] { return window->controller()->runState() == qt::RunState::Ready; }));
  ASSERT_TRUE(waitUntil([&] { return window->currentSnapshot()->time == 0.0; }));
  EXPECT_LT((window->currentSnapshot()->positions - placed->positions).norm(), 1e-12);
  EXPECT_TRUE(dialogs.errors.empty());
}

TEST_F(MainWindowTest, MalformedFileShowsTheLoaderMessageAndKeepsTheScene) {
  drapeSteps(3);
  const auto before = window->currentSnapshot();
  const std::filesystem::path pattern = window->document()->scene().patternFile;
  for (const char* name :
       {"pattern_endpoint_out_of_range.json", "scene_unknown_fabric.json", "scene_invalid_json.json"}) {
    const std::filesystem::path bad = testDataDir() / "bad" / name;
    std::string expected;
    try {
      loadScene(coarseState(bad).request());
    } catch (const InputError& e) {
      expected = e.what();
    }
    ASSERT_FALSE(expected.empty());
    dialogs.errors.clear();
    EXPECT_FALSE(window->openFile(bad));
    ASSERT_EQ(dialogs.errors.size(), 1u) << name;
    EXPECT_EQ(dialogs.errors[0], expected);
    EXPECT_NE(window->logView()->toPlainText().indexOf(QString::fromStdString(expected).toHtmlEscaped().left(20)), -1);
  }
  QTest::qWait(100);
  EXPECT_EQ(window->document()->scene().patternFile, pattern);
  EXPECT_EQ(window->currentSnapshot(), before) << "the draped state is still shown";
  EXPECT_EQ(window->controller()->runState(), qt::RunState::Paused);
  EXPECT_TRUE(window->simulationActions().resume->isEnabled());
}

TEST_F(MainWindowTest, FabricEditInTheDockUndoesAndRedoes) {
  QLineEdit* edit = window->fabricPanel()->editor("fabric.stretch_warp");
  ASSERT_NE(edit, nullptr);
  const double original = loadFabricPreset("cotton_shirting").stretchWarp;
  EXPECT_EQ(edit->text().toDouble(), original);
  EXPECT_FALSE(window->undoAction()->isEnabled());
  edit->setFocus();
  edit->selectAll();
  QTest::keyClicks(edit, "4321");
  QTest::keyClick(edit, Qt::Key_Return);
  EXPECT_EQ(window->document()->scene().fabric.stretchWarp, 4321.0);
  EXPECT_TRUE(window->undoAction()->isEnabled());
  EXPECT_TRUE(window->isWindowModified());
  window->undoAction()->trigger();
  EXPECT_EQ(window->document()->scene().fabric.stretchWarp, original);
  EXPECT_EQ(window->fabricPanel()->editor("fabric.stretch_warp")->text().toDouble(), original);
  EXPECT_FALSE(window->isWindowModified());
  window->redoAction()->trigger();
  EXPECT_EQ(window->fabricPanel()->editor("fabric.stretch_warp")->text().toDouble(), 4321.0);

  // The preset chooser: denim's parameters appear in the dock.
  QComboBox* presets = window->fabricPanel()->presetChooser();
  const int denim = presets->findText("denim");
  ASSERT_GE(denim, 0);
  presets->setCurrentIndex(denim);
  emit presets->textActivated("denim");
  EXPECT_EQ(window->fabricPanel()->editor("fabric.stretch_warp")->text().toDouble(),
            loadFabricPreset("denim").stretchWarp);
  EXPECT_TRUE(dialogs.errors.empty());
}

TEST_F(MainWindowTest, SettingsTableListsEverySettingAndEditsAreUndoable) {
  qt::SettingsTable* table = window->simulationPanel()->settingsTable();
  const auto& specs = Settings::specs();
  ASSERT_EQ(table->rowCount(), static_cast<int>(specs.size()));
  const Settings& settings = window->document()->scene().settings;
  for (size_t i = 0; i < specs.size(); ++i) {
    EXPECT_EQ(table->item(static_cast<int>(i), 0)->text().toStdString(), specs[i].key);
    EXPECT_EQ(table->item(static_cast<int>(i), 2)->text().toStdString(), specs[i].unit);
    const std::string shown = table->valueText(static_cast<int>(i)).toStdString();
    EXPECT_EQ(shown, settings.has(specs[i].key) ? settings.text(specs[i].key) : std::string()) << specs[i].key;
  }
  table->editValue("solver.newton.max_iterations", "7");
  EXPECT_EQ(window->document()->scene().settings.integer("solver.newton.max_iterations"), 7);
  table->editValue("solver.newton.max_iterations", "-2");
  ASSERT_EQ(dialogs.errors.size(), 1u);
  EXPECT_NE(dialogs.errors[0].find("solver.newton.max_iterations"), std::string::npos);
  EXPECT_EQ(table->valueText(table->rowOf("solver.newton.max_iterations")), "7") << "the table shows the kept value";
  window->undoAction()->trigger();
  EXPECT_EQ(window->document()->scene().settings.integer("solver.newton.max_iterations"), 5);
  EXPECT_EQ(table->valueText(table->rowOf("solver.newton.max_iterations")), "5");
}

TEST_F(MainWindowTest, SpeedAccuracySliderSetsTheSolverSettings) {
  // The levels come from assets/trade/speed_accuracy_levels.json (drape --trade-levels).
  ASSERT_TRUE(window->simulationPanel()->levelsError().isEmpty())
      << window->simulationPanel()->levelsError().toStdString();
  QSlider* slider = window->simulationPanel()->speedAccuracySlider();
  ASSERT_TRUE(slider->isEnabled());
  slider->setValue(0);
  emit slider->sliderReleased();
  const auto& fastest = qt::speedAccuracyLevels().front();
  const Settings& s = window->document()->scene().settings;
  for (const auto& [key, value] : fastest.settings) EXPECT_EQ(s.number(key), std::stod(value)) << key;
  EXPECT_EQ(qt::nearestSpeedAccuracyLevel(s), 0);
  window->undoAction()->trigger();
  EXPECT_EQ(window->document()->scene().settings.number("mesh.target_edge_length"), 0.1);
}

// Each position's tooltip says what its level costs and buys on the reference scene, with the numbers of the
// levels file, and then the settings it sets.
TEST_F(MainWindowTest, SpeedAccuracySliderSaysWhatEachLevelCostsAndBuys) {
  QSlider* slider = window->simulationPanel()->speedAccuracySlider();
  const auto& levels = qt::speedAccuracyLevels();
  ASSERT_EQ(slider->maximum() + 1, static_cast<int>(levels.size()));
  for (int i = 0; i < static_cast<int>(levels.size()); ++i) {
    slider->setValue(i);
    const QString tip = slider->toolTip();
    const auto& level = levels[static_cast<size_t>(i)];
    EXPECT_TRUE(tip.contains(QString::fromStdString(level.name))) << tip.toStdString();
    EXPECT_TRUE(tip.contains(QString::fromStdString(level.summary).toHtmlEscaped())) << tip.toStdString();
    EXPECT_NE(level.summary.find(" mm from the reference"), std::string::npos) << level.summary;
    const long seconds = std::lround(level.wallSeconds);
    if (level.wallSeconds >= 3) {
      EXPECT_NE(level.summary.find("about " + std::to_string(seconds) + " s"), std::string::npos) << level.summary;
    }
    EXPECT_TRUE(tip.contains("h_max")) << tip.toStdString();
  }
}

TEST_F(MainWindowTest, ExportWritesTheDrapedPositionsAndScreenshotWritesAPng) {
  drapeSteps(3);
  const auto snapshot = window->currentSnapshot();
  const std::filesystem::path obj = testOutputDir() / "gui_export.obj";
  std::filesystem::remove(obj);
  ASSERT_TRUE(window->exportGarment(obj)) << (dialogs.errors.empty() ? "" : dialogs.errors[0]);
  std::ifstream in(obj);
  std::string line;
  int v = 0;
  double maxError = 0.0;
  while (std::getline(in, line)) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream ls(line.substr(2));
    double x, y, z;
    ls >> x >> y >> z;
    ASSERT_LT(v, snapshot->positions.rows());
    maxError = std::max(maxError, (Eigen::Vector3d(x, y, z) - snapshot->positions.row(v).transpose()).norm());
    ++v;
  }
  EXPECT_EQ(v, snapshot->positions.rows());
  EXPECT_LT(maxError, 1e-6);

  const std::filesystem::path png = testOutputDir() / "gui_screenshot.png";
  std::filesystem::remove(png);
  ASSERT_TRUE(window->saveScreenshot(png));
  QImage image(QString::fromStdString(png.string()));
  ASSERT_FALSE(image.isNull());
  EXPECT_EQ(image.size(), window->viewport()->grabFramebuffer().size());

  EXPECT_FALSE(window->exportGarment(testOutputDir() / "garment.xyz"));
  ASSERT_EQ(dialogs.errors.size(), 1u);
  EXPECT_NE(dialogs.errors[0].find("garment.xyz"), std::string::npos);
}

TEST_F(MainWindowTest, LoadedGarmentStateIsShownAndTheDrapeContinuesFromIt) {
  const auto placed = window->currentSnapshot();
  Eigen::MatrixX3d lifted = placed->positions;
  lifted.col(1).array() += 0.03;
  const std::filesystem::path obj = testOutputDir() / "gui_state.obj";
  drape::exportGarment(*window->document()->garment(), lifted, obj);

  ASSERT_TRUE(window->loadGarmentState(obj)) << (dialogs.errors.empty() ? "" : dialogs.errors[0]);
  ASSERT_TRUE(waitUntil([&] {
    const auto s = window->currentSnapshot();
    return s && (s->positions - lifted).cwiseAbs().maxCoeff() < 1e-6;
  }));
  EXPECT_FALSE(window->undoAction()->isEnabled()) << "loading a state is not an edit of the scene";
  // The worker's simulation starts from it (this scene's stage is drape: the drape, as from a preview's hand-over).
  ASSERT_TRUE(waitUntil([&] { return window->controller()->latestResumeState().has_value(); }));
  const ResumeState resume = *window->controller()->latestResumeState();
  EXPECT_EQ(resume.stage, Stage::Drape);
  ASSERT_EQ(resume.previewPositions.rows(), lifted.rows());
  EXPECT_LT((resume.previewPositions - lifted).cwiseAbs().maxCoeff(), 1e-6);
  drapeSteps(1);
  EXPECT_GT(window->currentSnapshot()->time, 0.0);
  EXPECT_EQ(window->currentSnapshot()->stage, Stage::Drape);
  EXPECT_TRUE(dialogs.errors.empty());

  // Another garment's state: the dialog names the file, the running state stays.
  const std::filesystem::path other = testOutputDir() / "gui_state_other.obj";
  std::ofstream(other) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const auto before = window->currentSnapshot();
  EXPECT_FALSE(window->loadGarmentState(other));
  ASSERT_EQ(dialogs.errors.size(), 1u);
  EXPECT_NE(dialogs.errors[0].find("gui_state_other.obj: 3 vertices, the scene's garment has"), std::string::npos)
      << dialogs.errors[0];
  QTest::qWait(100);
  EXPECT_EQ(window->currentSnapshot(), before);
}

TEST_F(MainWindowTest, UnsavedChangesPromptOnClose) {
  ASSERT_TRUE(window->document()->setSetting("fabric.friction", "0.9"));
  dialogs.answer = qt::UserDialogs::SaveChoice::Cancel;
  EXPECT_FALSE(window->close());
  EXPECT_EQ(dialogs.saveQuestions, 1);
  EXPECT_TRUE(window->isVisible());
  dialogs.answer = qt::UserDialogs::SaveChoice::Discard;
  EXPECT_TRUE(window->close());
  EXPECT_EQ(dialogs.saveQuestions, 2);
  window.reset();
}

TEST_F(MainWindowTest, ClosingDuringADrapeIsSafe) {
  window->simulationActions().drape->trigger();
  ASSERT_TRUE(waitUntil([&] { return window->statisticsPanel()->steps() >= 1; }));
  EXPECT_TRUE(window->close());
  window.reset();  // joins the worker
  SUCCEED();
}

// A scene whose avatar file is in centimetres but says no unit: the body comes out 100 times too tall, and the log
// says which unit it looks like.
TEST_F(MainWindowTest, AvatarInCentimetresIsWarnedAboutInTheLog) {
  const std::filesystem::path dir = testOutputDir() / "gui_avatar_units";
  std::filesystem::create_directories(dir);
  test::writeScaledObj(assetsDir() / "avatars" / "female.obj", 100.0, dir / "female_cm.obj");
  std::ofstream(dir / "scene.json") << R"({"pattern": ")" << (assetsDir() / "patterns" / "tshirt.json").generic_string()
                                    << R"(", "avatar": {"file": "female_cm.obj"}})";
  ASSERT_TRUE(window->openFile(dir / "scene.json"));
  const QString log = window->logView()->toPlainText();
  EXPECT_NE(log.indexOf("female_cm.obj: the avatar is "), -1) << log.toStdString();
  EXPECT_NE(log.indexOf("it looks like centimetres: load it with --avatar-units cm"), -1) << log.toStdString();
}

TEST_F(MainWindowTest, RecentFilesRememberOpenedScenes) {
  const QStringList recent = qt::MainWindow::recentFiles();
  ASSERT_FALSE(recent.isEmpty());
  EXPECT_EQ(std::filesystem::canonical(recent.front().toStdString()), std::filesystem::canonical(defaultScene()));
}

}  // namespace
}  // namespace drape::test
