#include "drape/qt/pattern_view.h"

#include <QAction>
#include <QComboBox>
#include <QKeyEvent>
#include <QLabel>
#include <QMouseEvent>
#include <QScrollBar>
#include <QToolBar>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <cmath>

namespace drape::qt {

PatternView::PatternView(PatternSheet* sheet, QWidget* parent) : QGraphicsView(sheet, parent) {
  setObjectName("PatternView");
  setRenderHint(QPainter::Antialiasing);
  setTransformationAnchor(QGraphicsView::AnchorUnderMouse);
  setDragMode(QGraphicsView::NoDrag);
  setMinimumSize(200, 160);
  // Until the user zooms, the view keeps the whole sheet in sight, whatever the pattern.
  connect(sheet, &QGraphicsScene::sceneRectChanged, this, [this] {
    if (!m_userZoomed) fit();
  });
}

void PatternView::fitToView() {
  m_userZoomed = false;
  fit();
}

void PatternView::fit() {
  auto* sheet = static_cast<PatternSheet*>(scene());
  QRectF r = sheet->panelsRect();
  if (!sheet->checkSquareRect().isEmpty()) r |= sheet->checkSquareRect();
  if (r.isEmpty()) return;
  const double margin = 0.04 * std::max(r.width(), r.height());
  fitInView(r.adjusted(-margin, -margin, margin, margin), Qt::KeepAspectRatio);
}

void PatternView::wheelEvent(QWheelEvent* event) {
  const double factor = std::pow(1.0015, event->angleDelta().y());
  m_userZoomed = true;
  scale(factor, factor);
  event->accept();
}

void PatternView::mousePressEvent(QMouseEvent* event) {
  if (event->button() == Qt::MiddleButton || event->button() == Qt::RightButton) {
    m_panning = true;
    m_panFrom = event->pos();
    setCursor(Qt::ClosedHandCursor);
    event->accept();
    return;
  }
  QGraphicsView::mousePressEvent(event);
}

void PatternView::mouseMoveEvent(QMouseEvent* event) {
  if (m_panning) {
    const QPoint d = event->pos() - m_panFrom;
    m_panFrom = event->pos();
    horizontalScrollBar()->setValue(horizontalScrollBar()->value() - d.x());
    verticalScrollBar()->setValue(verticalScrollBar()->value() - d.y());
    m_userZoomed = true;
    event->accept();
    return;
  }
  QGraphicsView::mouseMoveEvent(event);
}

void PatternView::mouseReleaseEvent(QMouseEvent* event) {
  if (m_panning) {
    m_panning = false;
    unsetCursor();
    event->accept();
    return;
  }
  QGraphicsView::mouseReleaseEvent(event);
}

void PatternView::keyPressEvent(QKeyEvent* event) {
  if (event->key() == Qt::Key_F && !(event->modifiers() & Qt::ControlModifier)) {
    fitToView();
    return;
  }
  if (event->key() == Qt::Key_R) {
    // R turns the selected panel 15 degrees clockwise on the sheet, Shift+R back.
    auto* sheet = static_cast<PatternSheet*>(scene());
    if (sheet->rotateSelectedPanel(event->modifiers() & Qt::ShiftModifier ? -15.0 : 15.0)) return;
  }
  if ((event->key() == Qt::Key_Delete || event->key() == Qt::Key_Backspace) &&
      static_cast<PatternSheet*>(scene())->deleteSelectedVertex())
    return;
  QGraphicsView::keyPressEvent(event);
}

void PatternView::resizeEvent(QResizeEvent* event) {
  QGraphicsView::resizeEvent(event);
  if (!m_userZoomed) fit();
}

PatternPanel::PatternPanel(PatternSheet* sheet, QWidget* parent) : QWidget(parent), m_sheet(sheet) {
  setObjectName("PatternPanel");
  m_view = new PatternView(sheet);
  auto* bar = new QToolBar;
  bar->setIconSize(QSize(16, 16));
  auto* fit = bar->addAction(tr("Fit"));
  fit->setToolTip(tr("Fit every panel in the view (F)"));
  connect(fit, &QAction::triggered, m_view, &PatternView::fitToView);
  m_sew = bar->addAction(tr("Sew"));
  m_sew->setToolTip(tr("Sew two edges: click the first edge, then the second (an edge selected now is the first)"));
  connect(m_sew, &QAction::triggered, sheet, &PatternSheet::startSewing);
  m_unpick = bar->addAction(tr("Unpick"));
  m_unpick->setToolTip(tr("Remove the selected seam"));
  connect(m_unpick, &QAction::triggered, sheet, [sheet] { sheet->unpickSelectedSeam(); });
  m_map = new QComboBox;
  m_map->addItem(tr("Panels"), static_cast<int>(SheetMap::None));
  m_map->addItem(tr("Strain"), static_cast<int>(SheetMap::Strain));
  m_map->addItem(tr("Contacts"), static_cast<int>(SheetMap::Contacts));
  m_map->setToolTip(tr("Colour the flat panels by the drape's strain or contacts, as in 3D"));
  bar->addWidget(m_map);
  m_legend = new QLabel;
  m_legend->setObjectName("PatternMapLegend");
  bar->addWidget(m_legend);
  // The sheet's map changes with each snapshot (setMap); the scale follows after it is drawn.
  connect(sheet, &QGraphicsScene::changed, m_legend, [this] { m_legend->setText(legend()); });
  connect(m_map, &QComboBox::activated, this,
          [this](int index) { emit mapChosen(static_cast<SheetMap>(m_map->itemData(index).toInt())); });
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  layout->addWidget(bar);
  layout->addWidget(m_view);
}

QString PatternPanel::legend() const {
  if (m_sheet->map() != SheetMap::Strain || m_sheet->strainScale() <= 0.0) return {};
  return tr(" strain 0 - %1 %").arg(100.0 * m_sheet->strainScale(), 0, 'g', 3);
}

}  // namespace drape::qt
