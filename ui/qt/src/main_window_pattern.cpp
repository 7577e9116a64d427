// MainWindow: the pattern view beside the drape (linked selection, pattern edits, the maps on the flat panels,
// writing the pattern out).
#include <QAction>
#include <QComboBox>
#include <QFileDialog>
#include <QImage>
#include <QTimer>
#include <QUndoCommand>
#include <QUndoStack>
#include <algorithm>
#include <cstring>

#include "drape/core/input_error.h"
#include "drape/pattern/pattern_edit.h"
#include "drape/qt/main_window.h"
#include "drape/qt/pattern_print.h"
#include "drape/qt/pattern_sheet.h"
#include "drape/qt/pattern_view.h"
#include "drape/qt/scene_document.h"
#include "drape/qt/scene_panel.h"
#include "drape/qt/simulation_controller.h"
#include "drape/qt/viewport_widget.h"

namespace drape::qt {
namespace {

// A panel moved on the sheet. The sheet has already moved it when the command is pushed.
class LayoutCommand : public QUndoCommand {
 public:
  LayoutCommand(PatternSheet* sheet, SheetLayout before, SheetLayout after, const QString& text)
      : QUndoCommand(text), m_sheet(sheet), m_before(std::move(before)), m_after(std::move(after)) {}
  void redo() override {
    if (m_first)
      m_first = false;
    else
      m_sheet->setLayout(m_after);
  }
  void undo() override { m_sheet->setLayout(m_before); }

 private:
  PatternSheet* m_sheet;
  SheetLayout m_before, m_after;
  bool m_first = true;
};

}  // namespace

void MainWindow::connectPatternView() {
  connect(m_document, &SceneDocument::sceneChanged, this, [this] {
    if (!m_document->hasScene()) return;
    m_sheet->setPattern(m_document->scene().pattern);
    showSelectionIn3d();
  });
  connect(m_sheet, &PatternSheet::selectionChanged, this, [this] { showSelectionIn3d(); });
  connect(m_scenePanel, &ScenePanel::panelClicked, this, [this](int panel) {
    m_sheet->setSelection({panel, -1, -1});
    showSelectionIn3d();
  });
  connect(m_viewport, &ViewportWidget::garmentClicked, this, [this](int vertex) {
    const auto garment = m_document->garment();
    if (!garment || vertex < 0 || vertex >= garment->vertexCount()) return;
    // The panel under the cursor; on its outline (the nearest vertex of the hit triangle is an edge's), the edge, and
    // the seam when the edge is sewn.
    const int panel = garment->vertexPanel(vertex);
    PatternSelection selection{panel, -1, -1};
    const auto& edges = garment->edgeVertices[static_cast<size_t>(panel)];
    for (size_t e = 0; e < edges.size() && selection.edge < 0; ++e)
      if (std::find(edges[e].begin(), edges[e].end(), vertex) != edges[e].end()) selection.edge = static_cast<int>(e);
    if (selection.edge >= 0) selection.stitch = seamOfEdge(m_document->scene().pattern, panel, selection.edge);
    m_sheet->setSelection(selection);
    showSelectionIn3d();
  });
  connect(m_sheet, &PatternSheet::patternEdited, this,
          [this](const Pattern& pattern, const QString& text) { m_document->setPattern(pattern, text); });
  connect(m_sheet, &PatternSheet::editRefused, this,
          [this](const QString& message) { showError(tr("Edit pattern"), message); });
  connect(m_sheet, &PatternSheet::layoutEdited, this,
          [this](const SheetLayout& before, const SheetLayout& after, const QString& text) {
            m_document->undoStack()->push(new LayoutCommand(m_sheet, before, after, text));
          });
  // The map follows the simulation at most four times a second: rebuilding it costs a pass over every triangle.
  auto* mapTimer = new QTimer(this);
  mapTimer->setSingleShot(true);
  mapTimer->setInterval(250);
  connect(mapTimer, &QTimer::timeout, this, [this] {
    if (m_snapshot) m_sheet->setMap(m_sheet->map(), *m_snapshot);
  });
  connect(m_controller, &SimulationController::snapshotReady, this, [this, mapTimer] {
    if (m_sheet->map() != SheetMap::None && !mapTimer->isActive()) mapTimer->start();
  });
  connect(m_patternPanel, &PatternPanel::mapChosen, this,
          [this](SheetMap map) { m_sheet->setMap(map, m_snapshot ? *m_snapshot : Snapshot()); });
}

void MainWindow::showSelectionIn3d() {
  const PatternSelection s = m_sheet->selection();
  const auto garment = m_document->garment();
  std::vector<int> panels;
  std::vector<std::vector<int>> chains;
  auto edgeChain = [&](int panel, int edge) {
    if (panel >= 0 && panel < static_cast<int>(garment->edgeVertices.size()) && edge >= 0 &&
        edge < static_cast<int>(garment->edgeVertices[static_cast<size_t>(panel)].size()))
      chains.push_back(garment->edgeVertices[static_cast<size_t>(panel)][static_cast<size_t>(edge)]);
  };
  if (garment && m_document->hasScene()) {
    const Pattern& pattern = m_document->scene().pattern;
    if (s.stitch >= 0 && s.stitch < static_cast<int>(pattern.stitches.size())) {
      const Stitch& st = pattern.stitches[static_cast<size_t>(s.stitch)];
      edgeChain(st.a.panel, st.a.edge);
      edgeChain(st.b.panel, st.b.edge);
    } else if (s.edge >= 0) {
      edgeChain(s.panel, s.edge);
    } else if (s.panel >= 0) {
      panels.push_back(s.panel);
    }
  }
  m_viewport->setHighlight(std::move(panels), std::move(chains));
  m_scenePanel->selectPanel(s.panel);
}

bool MainWindow::savePatternAs(const std::filesystem::path& file) {
  if (!m_document->hasScene()) return false;
  try {
    writePatternFile(m_document->scene().pattern, file);
  } catch (const InputError& e) {
    showError(tr("Save pattern"), QString::fromStdString(e.what()));
    return false;
  }
  log(tr("info"), tr("Saved the pattern to %1").arg(QString::fromStdString(file.string())));
  return true;
}

bool MainWindow::showPrint(const std::filesystem::path& file) {
  QImage image(QString::fromStdString(file.string()));
  if (image.isNull()) {
    showError(tr("Fabric print"), tr("%1: not an image Qt can read").arg(QString::fromStdString(file.string())));
    return false;
  }
  image = image.convertToFormat(QImage::Format_RGBA8888);
  auto print = std::make_shared<render::Image>(image.width(), image.height());
  for (int y = 0; y < image.height(); ++y)
    std::memcpy(print->at(0, y), image.constScanLine(y), static_cast<size_t>(image.width()) * 4);
  render::RenderOptions options = m_viewport->renderOptions();
  options.print = std::move(print);
  const double dotsPerMetre = image.dotsPerMeterX() > 0 ? image.dotsPerMeterX() : 96.0 / 0.0254;
  options.printWidth = image.width() / dotsPerMetre;
  options.mode = render::DisplayMode::Print;
  m_viewport->setRenderOptions(options);
  m_displayMode->setCurrentIndex(m_displayMode->findData(static_cast<int>(render::DisplayMode::Print)));
  log(tr("info"), tr("Print %1 on the garment: %2 x %3 cm per repeat")
                      .arg(QString::fromStdString(file.filename().string()))
                      .arg(100.0 * options.printWidth, 0, 'f', 1)
                      .arg(100.0 * options.printWidth * image.height() / image.width(), 0, 'f', 1));
  return true;
}

void MainWindow::onShowPrint() {
  const QString file = QFileDialog::getOpenFileName(this, tr("Fabric print"), QString(),
                                                    tr("Images (*.png *.jpg *.jpeg *.bmp);;All files (*)"));
  if (!file.isEmpty()) showPrint(std::filesystem::path(file.toStdString()));
}

void MainWindow::onSavePattern() {
  const QString file = QFileDialog::getSaveFileName(
      this, tr("Save pattern"), QStringLiteral("pattern.json"),
      tr("GarmentCode JSON (*.json);;DXF-AAMA (*.dxf);;PDF at full scale (*.pdf);;SVG at full scale (*.svg)"));
  if (!file.isEmpty()) savePatternAs(std::filesystem::path(file.toStdString()));
}

}  // namespace drape::qt
