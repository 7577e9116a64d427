// The pattern view beside the drape (issue #65) under Xvfb: the flat panels and their seams, selection linked both
// ways with the 3D viewport, edits by mouse (move, insert and delete a vertex, sew, unpick) that re-mesh and carry
// the running drape over, refusals with the loader's message, undo and redo, the maps on the flat panels, and the
// pattern written out.
#include "drape/qt/pattern_view.h"

#include <QAction>
#include <QComboBox>
#include <QImage>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QTreeWidget>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <fstream>

#include "drape/pattern/dxf_aama.h"
#include "drape/pattern/edge_curve.h"
#include "drape/pattern/pattern_edit.h"
#include "drape/pattern/pattern_loader.h"
#include "drape/qt/main_window.h"
#include "drape/qt/pattern_sheet.h"
#include "drape/qt/scene_panel.h"
#include "drape/qt/simulation_controller.h"
#include "drape/qt/viewport_widget.h"
#include "gui_test_support.h"

namespace drape::test {
namespace {

class PatternViewTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!guiHaveDisplay()) GTEST_SKIP() << "no display: run under xvfb-run -a";
    guiApplication();
    window = std::make_unique<qt::MainWindow>(&dialogs);
    window->document()->setBaseOverrides(coarseOverrides());
    window->resize(1300, 850);
    window->show();
    ASSERT_TRUE(QTest::qWaitForWindowExposed(window.get()));
    ASSERT_TRUE(window->openFile(assetsDir() / "scenes" / "tshirt.json"));
    ASSERT_TRUE(waitUntil([&] { return window->currentSnapshot() != nullptr; }));
    placed = window->currentSnapshot();
    ASSERT_TRUE(waitUntil([&] { return sheet()->panelRect(0).isValid(); }));
    view()->fitToView();
    QApplication::processEvents();
  }
  void TearDown() override {
    if (window) {
      dialogs.answer = qt::UserDialogs::SaveChoice::Discard;
      window->close();
    }
  }
  qt::PatternSheet* sheet() const { return window->patternSheet(); }
  qt::PatternView* view() const { return window->patternPanel()->view(); }
  const Pattern& pattern() const { return window->document()->scene().pattern; }
  QPoint onView(int panel, const Eigen::Vector2d& p) const { return view()->mapFromScene(sheet()->toScene(panel, p)); }
  // A point inside panel p: the pattern coordinates (file units) of an interior mesh vertex of that panel.
  Eigen::Vector2d insidePanel(int panel) const {
    const Garment& g = *window->document()->garment();
    std::vector<bool> boundary(static_cast<size_t>(g.vertexCount()), false);
    for (const auto& edges : g.edgeVertices)
      for (const auto& chain : edges)
        for (int v : chain) boundary[static_cast<size_t>(v)] = true;
    for (int v = 0; v < g.vertexCount(); ++v)
      if (g.vertexPanel(v) == panel && !boundary[static_cast<size_t>(v)])
        return Eigen::Vector2d(g.uvs(v, 0), g.uvs(v, 1)) * pattern().unitsInMeter;
    return Eigen::Vector2d::Zero();
  }
  void click(const QPoint& at) {
    QTest::mouseClick(view()->viewport(), Qt::LeftButton, Qt::NoModifier, at);
    QApplication::processEvents();
  }
  // The middle of edge e of panel p, on the view.
  QPoint edgeMiddle(int panel, int edge) const {
    return onView(panel, evaluateEdge(pattern().panels[static_cast<size_t>(panel)], edge, 0.5));
  }
  void drag(const QPoint& from, const QPoint& to) {
    QWidget* w = view()->viewport();
    sendMouse(w, QEvent::MouseButtonPress, QPointF(from), Qt::LeftButton);
    for (int i = 1; i <= 5; ++i) sendMouse(w, QEvent::MouseMove, QPointF(from + (to - from) * i / 5), Qt::LeftButton);
    sendMouse(w, QEvent::MouseButtonRelease, QPointF(to), Qt::NoButton);
    QApplication::processEvents();
  }
  // A panel and one of its unsewn edges.
  std::pair<int, int> unsewnEdge() const {
    for (int p = 0; p < static_cast<int>(pattern().panels.size()); ++p)
      for (int e = 0; e < static_cast<int>(pattern().panels[static_cast<size_t>(p)].edges.size()); ++e)
        if (seamOfEdge(pattern(), p, e) < 0) return {p, e};
    return {-1, -1};
  }

  RecordingDialogs dialogs;
  std::unique_ptr<qt::MainWindow> window;
  std::shared_ptr<const Snapshot> placed;
};

// Pixels of the viewport's image of the highlight's orange hue (230, 126, 34 is 28 degrees), whatever the shading.
int orangePixels(qt::ViewportWidget* viewport) {
  const QImage image = viewport->grabFramebuffer();
  int count = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QColor c = image.pixelColor(x, y);
      count += c.hsvHue() >= 15 && c.hsvHue() <= 40 && c.hsvSaturation() > 90 && c.value() > 50;
    }
  return count;
}

// The mean over the vertices of `of` of the distance to the nearest vertex of `to`.
double meanNearest(const Eigen::MatrixX3d& of, const Eigen::MatrixX3d& to) {
  double sum = 0.0;
  for (Eigen::Index v = 0; v < of.rows(); ++v) {
    double nearest = INFINITY;
    for (Eigen::Index u = 0; u < to.rows(); ++u) nearest = std::min(nearest, (of.row(v) - to.row(u)).squaredNorm());
    sum += std::sqrt(nearest);
  }
  return sum / static_cast<double>(of.rows());
}

TEST_F(PatternViewTest, ShowsEveryPanelAtFullScaleAndEachSeamAsAPairOfColouredEdges) {
  const Pattern& p = pattern();
  ASSERT_GE(p.stitches.size(), 4u);
  const double k = 1000.0 / p.unitsInMeter;  // mm per file unit
  for (int i = 0; i < static_cast<int>(p.panels.size()); ++i) {
    const QRectF r = sheet()->panelRect(i);
    // The outline's extent, from the curves sampled independently of the sheet.
    double minX = INFINITY, maxX = -INFINITY, minY = INFINITY, maxY = -INFINITY;
    for (const Eigen::Vector2d& q : panelOutline(p.panels[static_cast<size_t>(i)], 0.1)) {
      minX = std::min(minX, q.x()), maxX = std::max(maxX, q.x());
      minY = std::min(minY, q.y()), maxY = std::max(maxY, q.y());
    }
    EXPECT_NEAR(r.width(), (maxX - minX) * k, 2.0) << p.panels[static_cast<size_t>(i)].name;
    EXPECT_NEAR(r.height(), (maxY - minY) * k, 2.0) << p.panels[static_cast<size_t>(i)].name;
    for (int j = 0; j < i; ++j) EXPECT_FALSE(r.intersects(sheet()->panelRect(j))) << i << " overlaps " << j;
  }
  std::vector<QColor> seams;
  for (const Stitch& s : p.stitches) {
    const QColor a = sheet()->edgeColor(s.a.panel, s.a.edge), b = sheet()->edgeColor(s.b.panel, s.b.edge);
    ASSERT_TRUE(a.isValid() && b.isValid());
    EXPECT_EQ(a, b);
    for (const QColor& other : seams) EXPECT_NE(a, other);
    seams.push_back(a);
  }
  const auto [panel, edge] = unsewnEdge();
  ASSERT_GE(panel, 0);
  for (const QColor& seam : seams) EXPECT_NE(sheet()->edgeColor(panel, edge), seam);
}

TEST_F(PatternViewTest, SelectionIsLinkedBothWays) {
  const int plain = orangePixels(window->viewport());
  // A click on a flat panel selects it and lights it in 3D.
  const int panel = 1;
  click(onView(panel, insidePanel(panel)));
  EXPECT_EQ(sheet()->selection().panel, panel);
  EXPECT_EQ(sheet()->selection().edge, -1);
  EXPECT_EQ(window->viewport()->highlightedPanels(), std::vector<int>{panel});
  // ... and in the Scene dock's list; a click on another panel's row there selects that one everywhere.
  QTreeWidget* tree = window->scenePanel()->tree();
  ASSERT_NE(tree->currentItem(), nullptr);
  EXPECT_EQ(tree->currentItem()->text(0).toStdString(), pattern().panels[panel].name);
  QTreeWidgetItem* row = tree->topLevelItem(0)->child(2);
  tree->scrollToItem(row);
  QTest::mouseClick(tree->viewport(), Qt::LeftButton, Qt::NoModifier, tree->visualItemRect(row).center());
  EXPECT_EQ(sheet()->selection().panel, 2);
  EXPECT_EQ(window->viewport()->highlightedPanels(), std::vector<int>{2});
  click(onView(panel, insidePanel(panel)));
  const int panelLit = orangePixels(window->viewport());
  EXPECT_GT(panelLit, plain + 500) << "the selected panel is not drawn in the highlight colour";
  // A click on a seam's edge selects the seam: both its edges are drawn in 3D along their garment vertices.
  const Stitch& seam = pattern().stitches[0];
  click(edgeMiddle(seam.a.panel, seam.a.edge));
  EXPECT_EQ(sheet()->selection().stitch, 0);
  const Garment& g = *window->document()->garment();
  ASSERT_EQ(window->viewport()->highlightedChains().size(), 2u);
  EXPECT_EQ(window->viewport()->highlightedChains()[0],
            g.edgeVertices[static_cast<size_t>(seam.a.panel)][static_cast<size_t>(seam.a.edge)]);
  EXPECT_EQ(window->viewport()->highlightedChains()[1],
            g.edgeVertices[static_cast<size_t>(seam.b.panel)][static_cast<size_t>(seam.b.edge)]);
  const int seamLit = orangePixels(window->viewport());
  EXPECT_GT(seamLit, plain + 50) << "the selected seam is not drawn over the garment";
  EXPECT_LT(seamLit, panelLit);
  // A click on the garment in 3D selects, in the pattern view, the panel under the cursor: inside the panel the
  // panel alone, on its outline the edge, and on a sewn edge the seam.
  qt::ViewportWidget* viewport = window->viewport();
  const Snapshot& s = *window->currentSnapshot();
  std::vector<bool> outline(static_cast<size_t>(g.vertexCount()), false);
  for (const auto& edges : g.edgeVertices)
    for (const auto& chain : edges)
      for (int v : chain) outline[static_cast<size_t>(v)] = true;
  bool inside = false, onSeam = false;
  for (int v = 0; v < g.vertexCount() && !(inside && onSeam); ++v) {
    const auto pos = viewport->widgetPosition(s.positions.row(v).transpose());
    if (!pos) continue;
    const QPoint pixel = pos->toPoint();  // where the click lands: on a seam, either panel's vertex may be nearest
    const int under = viewport->garmentVertexAt(pixel);
    if (under < 0) continue;
    const bool edgeVertex = outline[static_cast<size_t>(under)];
    if (edgeVertex ? onSeam : inside) continue;
    QTest::mouseClick(viewport, Qt::LeftButton, Qt::NoModifier, pixel);
    QApplication::processEvents();
    const qt::PatternSelection got = sheet()->selection();
    EXPECT_EQ(got.panel, g.vertexPanel(under));
    if (!edgeVertex) {
      EXPECT_EQ(got.edge, -1);
      inside = true;
    } else {
      ASSERT_GE(got.edge, 0);
      const auto& chain = g.edgeVertices[static_cast<size_t>(got.panel)][static_cast<size_t>(got.edge)];
      EXPECT_NE(std::find(chain.begin(), chain.end(), under), chain.end());
      EXPECT_EQ(got.stitch, seamOfEdge(pattern(), got.panel, got.edge));
      onSeam = got.stitch >= 0;
    }
  }
  EXPECT_TRUE(inside);
  EXPECT_TRUE(onSeam);
}

TEST_F(PatternViewTest, DraggingAVertexReshapesTheGarmentAndTheDrapeCarriesOn) {
  // Let the preview run a little, then pause: the garment has left its placed state.
  const auto& actions = window->simulationActions();
  actions.preview->trigger();
  ASSERT_TRUE(waitUntil([&] { return window->currentSnapshot()->time > 0.15; }));
  actions.pause->trigger();
  ASSERT_TRUE(waitUntil([&] { return window->controller()->runState() == qt::RunState::Paused; }));
  QApplication::processEvents();
  const std::shared_ptr<const Snapshot> paused = window->currentSnapshot();
  const int undoBefore = window->document()->undoStack()->count();

  const auto [panel, edge] = unsewnEdge();
  const int vertex = pattern().panels[static_cast<size_t>(panel)].edges[static_cast<size_t>(edge)].start;
  const Eigen::Vector2d from = pattern().panels[static_cast<size_t>(panel)].vertices[static_cast<size_t>(vertex)];
  click(onView(panel, insidePanel(panel)));  // selecting the panel shows its handles
  // Outward by about 3 cm: away from the panel's interior point.
  const Eigen::Vector2d outward = (from - insidePanel(panel)).normalized() * 0.03 * pattern().unitsInMeter;
  drag(onView(panel, from), onView(panel, from + outward));
  ASSERT_TRUE(waitUntil([&] { return window->document()->undoStack()->count() == undoBefore + 1; }))
      << (dialogs.errors.empty() ? "" : dialogs.errors.back());
  const Eigen::Vector2d moved = pattern().panels[static_cast<size_t>(panel)].vertices[static_cast<size_t>(vertex)];
  // Where the mouse went, within two pixels of the view.
  const double pixel = 1.0 / view()->transform().m11() * pattern().unitsInMeter / 1000.0;
  EXPECT_NEAR((moved - (from + outward)).norm(), 0.0, 2.0 * pixel);
  // The drape goes on from where it was, on the new mesh: at its time, with the cloth near the paused drape rather
  // than back at the placed panels.
  ASSERT_TRUE(waitUntil([&] { return window->currentSnapshot() != paused; }));
  const Snapshot& now = *window->currentSnapshot();
  ASSERT_EQ(now.positions.rows(), window->document()->garment()->vertexCount());
  EXPECT_GE(now.time, paused->time);
  const double toDrape = meanNearest(now.positions, paused->positions);
  const double toPlaced = meanNearest(now.positions, placed->positions);
  EXPECT_LT(toDrape, 0.25 * toPlaced) << toDrape << " m from the drape, " << toPlaced << " m from the placed garment";

  window->undoAction()->trigger();
  ASSERT_TRUE(waitUntil([&] {
    return sheet()->pattern().panels[static_cast<size_t>(panel)].vertices[static_cast<size_t>(vertex)] == from;
  }));
  EXPECT_EQ(pattern().panels[static_cast<size_t>(panel)].vertices[static_cast<size_t>(vertex)], from);
  window->redoAction()->trigger();
  EXPECT_EQ(pattern().panels[static_cast<size_t>(panel)].vertices[static_cast<size_t>(vertex)], moved);
}

TEST_F(PatternViewTest, AnEditThatBreaksThePatternIsRefusedWithTheLoadersMessage) {
  const int panel = 0;
  const Panel p = pattern().panels[panel];
  // The leftmost corner dragged to the right of the whole panel, at mid height: the outline crosses itself.
  int corner = 0;
  Eigen::Vector2d low = p.vertices[0], high = p.vertices[0];
  for (size_t v = 0; v < p.vertices.size(); ++v) {
    if (p.vertices[v].x() < p.vertices[static_cast<size_t>(corner)].x()) corner = static_cast<int>(v);
    low = low.cwiseMin(p.vertices[v]);
    high = high.cwiseMax(p.vertices[v]);
  }
  const Eigen::Vector2d across(high.x() + 0.5 * (high.x() - low.x()), 0.5 * (low.y() + high.y()));
  const Eigen::Vector2d centre = insidePanel(panel);
  click(onView(panel, centre));
  const int undoBefore = window->document()->undoStack()->count();
  drag(onView(panel, p.vertices[static_cast<size_t>(corner)]), onView(panel, across));
  ASSERT_FALSE(dialogs.errors.empty()) << "undo " << window->document()->undoStack()->count() << " vs " << undoBefore
                                       << " corner now "
                                       << pattern().panels[panel].vertices[static_cast<size_t>(corner)].transpose()
                                       << " aimed " << across.transpose() << " from "
                                       << p.vertices[static_cast<size_t>(corner)].transpose();
  EXPECT_NE(dialogs.errors.back().find("panel '" + pattern().panels[panel].name + "'"), std::string::npos)
      << dialogs.errors.back();
  EXPECT_EQ(window->document()->undoStack()->count(), undoBefore);
  EXPECT_EQ(pattern().panels[panel].vertices[static_cast<size_t>(corner)], p.vertices[static_cast<size_t>(corner)]);
}

TEST_F(PatternViewTest, InsertDeleteSewAndUnpickByMouse) {
  const auto [panel, edge] = unsewnEdge();
  const size_t vertices = pattern().panels[static_cast<size_t>(panel)].vertices.size();
  // A double click on an edge inserts a vertex there.
  QTest::mouseDClick(view()->viewport(), Qt::LeftButton, Qt::NoModifier, edgeMiddle(panel, edge));
  ASSERT_TRUE(waitUntil([&] { return pattern().panels[static_cast<size_t>(panel)].vertices.size() == vertices + 1; }))
      << (dialogs.errors.empty() ? "" : dialogs.errors.back());
  // Its handle, focused by a click, goes with Delete.
  const Eigen::Vector2d added = pattern().panels[static_cast<size_t>(panel)].vertices.back();
  click(onView(panel, insidePanel(panel)));
  ASSERT_TRUE(waitUntil([&] { return sheet()->selection().panel == panel; }));
  QApplication::processEvents();
  click(onView(panel, added));
  QTest::keyClick(view(), Qt::Key_Delete);
  ASSERT_TRUE(waitUntil([&] { return pattern().panels[static_cast<size_t>(panel)].vertices.size() == vertices; }))
      << (dialogs.errors.empty() ? "" : dialogs.errors.back());

  // Unpick the first seam (selected by a click on its edge), then sew the same two edges again with Sew.
  const Stitch seam = pattern().stitches[0];
  const size_t seams = pattern().stitches.size();
  click(edgeMiddle(seam.a.panel, seam.a.edge));
  ASSERT_EQ(sheet()->selection().stitch, 0);
  window->patternPanel()->unpickAction()->trigger();
  ASSERT_TRUE(waitUntil([&] { return pattern().stitches.size() == seams - 1; }));
  QApplication::processEvents();
  click(edgeMiddle(seam.a.panel, seam.a.edge));
  window->patternPanel()->sewAction()->trigger();
  click(edgeMiddle(seam.b.panel, seam.b.edge));
  ASSERT_TRUE(waitUntil([&] { return pattern().stitches.size() == seams; }))
      << (dialogs.errors.empty() ? "" : dialogs.errors.back());
  const Stitch& sewn = pattern().stitches.back();
  EXPECT_EQ(sewn.a.panel, seam.a.panel);
  EXPECT_EQ(sewn.a.edge, seam.a.edge);
  EXPECT_EQ(sewn.b.panel, seam.b.panel);
  EXPECT_EQ(sewn.b.edge, seam.b.edge);
}

TEST_F(PatternViewTest, StrainMapCoversTheFlatPanels) {
  QComboBox* chooser = window->patternPanel()->mapChooser();
  chooser->setCurrentIndex(chooser->findData(static_cast<int>(qt::SheetMap::Strain)));
  emit chooser->activated(chooser->currentIndex());
  const Snapshot& s = *window->currentSnapshot();
  EXPECT_EQ(sheet()->map(), qt::SheetMap::Strain);
  EXPECT_EQ(sheet()->mapTriangleCount(), s.triangles.rows());
  EXPECT_GT(sheet()->strainScale(), 0.0);
  // Its scale is read beside the chooser, as the 3D legend gives it: the largest strain rounded up to 1, 2, 2.5 or
  // 5 x 10^k.
  double largest = 0.0;
  for (Eigen::Index f = 0; f < s.triangleStrain.size(); ++f) largest = std::max(largest, s.triangleStrain(f));
  EXPECT_GE(sheet()->strainScale(), largest);
  EXPECT_TRUE(window->patternPanel()->legend().startsWith(" strain 0 - "))
      << window->patternPanel()->legend().toStdString();
  chooser->setCurrentIndex(chooser->findData(static_cast<int>(qt::SheetMap::None)));
  emit chooser->activated(chooser->currentIndex());
  EXPECT_EQ(sheet()->mapTriangleCount(), 0);
  EXPECT_TRUE(window->patternPanel()->legend().isEmpty());
}

TEST_F(PatternViewTest, AFabricPrintShowsOnTheGarmentAtItsStatedSize) {
  // Stripes, red over blue, 600 x 600 pixels at 1200 dots per metre: a repeat of 50 cm.
  QImage stripes(600, 600, QImage::Format_RGB32);
  for (int y = 0; y < 600; ++y)
    for (int x = 0; x < 600; ++x) stripes.setPixelColor(x, y, (y / 50) % 2 ? QColor(30, 40, 200) : QColor(210, 30, 30));
  stripes.setDotsPerMeterX(1200);
  stripes.setDotsPerMeterY(1200);
  const std::filesystem::path file = std::filesystem::path(DRAPE_TEST_OUTPUT_DIR) / "pattern_view_print.png";
  ASSERT_TRUE(stripes.save(QString::fromStdString(file.string())));
  ASSERT_TRUE(window->showPrint(file));
  const render::RenderOptions& options = window->viewport()->renderOptions();
  EXPECT_EQ(options.mode, render::DisplayMode::Print);
  EXPECT_NEAR(options.printWidth, 0.5, 1e-12);
  // Both stripes show on the garment.
  const QImage shot = window->viewport()->grabFramebuffer();
  int red = 0, blue = 0;
  for (int y = 0; y < shot.height(); ++y)
    for (int x = 0; x < shot.width(); ++x) {
      const QColor c = shot.pixelColor(x, y);
      red += c.red() > c.blue() + 60 && c.red() > c.green() + 60;
      blue += c.blue() > c.red() + 60 && c.blue() > c.green() + 60;
    }
  EXPECT_GT(red, 300);
  EXPECT_GT(blue, 300);
  // A file that is no image: the dialog names it, the print stays.
  const std::filesystem::path bad = std::filesystem::path(DRAPE_TEST_OUTPUT_DIR) / "pattern_view_print.txt";
  { std::ofstream(bad) << "not an image"; }
  EXPECT_FALSE(window->showPrint(bad));
  ASSERT_FALSE(dialogs.errors.empty());
  EXPECT_NE(dialogs.errors.back().find("pattern_view_print.txt"), std::string::npos);
  EXPECT_NEAR(window->viewport()->renderOptions().printWidth, 0.5, 1e-12);
}

TEST_F(PatternViewTest, SavedPatternLoadsBackAsEdited) {
  const auto [panel, edge] = unsewnEdge();
  ASSERT_TRUE(window->document()->setPattern(insertVertex(pattern(), panel, edge, 0.5), "insert"));
  const std::filesystem::path file = std::filesystem::path(DRAPE_TEST_OUTPUT_DIR) / "pattern_view_saved.json";
  ASSERT_TRUE(window->savePatternAs(file));
  const Pattern loaded = loadPattern(file);
  ASSERT_EQ(loaded.panels.size(), pattern().panels.size());
  for (size_t p = 0; p < loaded.panels.size(); ++p) {
    EXPECT_EQ(loaded.panels[p].name, pattern().panels[p].name);
    EXPECT_EQ(loaded.panels[p].vertices, pattern().panels[p].vertices);
    EXPECT_EQ(loaded.panels[p].edges.size(), pattern().panels[p].edges.size());
  }
  EXPECT_EQ(loaded.stitches.size(), pattern().stitches.size());
  EXPECT_FALSE(window->savePatternAs(std::filesystem::path(DRAPE_TEST_OUTPUT_DIR) / "pattern_view_saved.txt"));
  EXPECT_NE(dialogs.errors.back().find("pattern_view_saved.txt"), std::string::npos);
}

// The DXF-AAMA flow: pieces from a garment CAD system open without seams, are sewn in the pattern view and saved as
// GarmentCode JSON with their seams.
TEST_F(PatternViewTest, DxfPiecesAreSewnInTheViewAndSavedAsGarmentCode) {
  const std::filesystem::path dxf = std::filesystem::path(DRAPE_TEST_OUTPUT_DIR) / "pattern_view_pieces.dxf";
  writeDxfAamaPattern(loadPattern(assetsDir() / "patterns" / "tshirt.json"), dxf);
  ASSERT_TRUE(window->openFile(dxf)) << (dialogs.errors.empty() ? "" : dialogs.errors.back());
  ASSERT_TRUE(waitUntil([&] { return sheet()->pattern().source == dxf.string() && sheet()->panelRect(5).isValid(); }));
  view()->fitToView();
  QApplication::processEvents();
  ASSERT_EQ(pattern().panels.size(), 6u);
  ASSERT_TRUE(pattern().stitches.empty());
  // Sew the first edge of the first two pieces.
  window->patternPanel()->sewAction()->trigger();
  click(edgeMiddle(0, 0));
  click(edgeMiddle(1, 0));
  ASSERT_TRUE(waitUntil([&] { return pattern().stitches.size() == 1; }))
      << (dialogs.errors.empty() ? "" : dialogs.errors.back());
  EXPECT_EQ(sheet()->edgeColor(0, 0), sheet()->edgeColor(1, 0));
  const std::filesystem::path json = std::filesystem::path(DRAPE_TEST_OUTPUT_DIR) / "pattern_view_sewn.json";
  ASSERT_TRUE(window->savePatternAs(json));
  const Pattern sewn = loadPattern(json);
  ASSERT_EQ(sewn.stitches.size(), 1u);
  EXPECT_EQ(sewn.stitches[0].a.panel, 0);
  EXPECT_EQ(sewn.stitches[0].a.edge, 0);
  EXPECT_EQ(sewn.stitches[0].b.panel, 1);
  EXPECT_EQ(sewn.stitches[0].b.edge, 0);
  EXPECT_EQ(sewn.panels[2].name, "l_sleeve_front");
}

}  // namespace
}  // namespace drape::test
