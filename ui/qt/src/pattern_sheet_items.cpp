#include "pattern_sheet_items.h"

#include <QGraphicsSceneMouseEvent>
#include <QGraphicsView>
#include <QPainter>
#include <QPainterPathStroker>
#include <QPen>

namespace drape::qt {
namespace {

constexpr double kHandlePixels = 9.0;

QPen edgePen(int stitch, bool highlighted) {
  QPen pen(stitch >= 0 ? seamColor(stitch) : QColor(60, 60, 66));
  pen.setCosmetic(true);
  pen.setWidthF((stitch >= 0 ? 3.0 : 1.5) + (highlighted ? 3.0 : 0.0));
  pen.setCapStyle(Qt::RoundCap);
  return pen;
}

}  // namespace

PanelItem::PanelItem(PatternSheet* sheet, int panel, const QColor& color)
    : m_sheet(sheet), m_panel(panel), m_color(color) {
  setFlag(ItemIsMovable, true);
  setHighlighted(false);
}

void PanelItem::setHighlighted(bool on) {
  QColor fill = m_color;
  fill.setAlphaF(on ? 0.75 : 0.4);
  setBrush(fill);
  QPen pen(on ? QColor(230, 126, 34) : Qt::transparent);
  pen.setCosmetic(true);
  pen.setWidthF(on ? 2.0 : 0.0);
  setPen(pen);
}

void PanelItem::mousePressEvent(QGraphicsSceneMouseEvent* event) {
  m_pressed = {pos(), rotation()};
  m_sheet->itemClicked({m_panel, -1, -1});
  QGraphicsPathItem::mousePressEvent(event);
}

void PanelItem::mouseReleaseEvent(QGraphicsSceneMouseEvent* event) {
  QGraphicsPathItem::mouseReleaseEvent(event);
  const PanelPlacement now{pos(), rotation()};
  if (!(now == m_pressed)) m_sheet->panelDragged(m_panel, m_pressed, now);
}

EdgeItem::EdgeItem(PatternSheet* sheet, int panel, int edge, int stitch, const QPainterPath& path)
    : QGraphicsPathItem(path), m_sheet(sheet), m_panel(panel), m_edge(edge), m_stitch(stitch) {
  setHighlighted(false);
}

QPainterPath EdgeItem::shape() const {
  // A band a few millimetres wide, wider when zoomed out, so that an edge is easy to hit.
  QPainterPathStroker stroker;
  const double scale = scene() && !scene()->views().isEmpty() ? scene()->views().first()->transform().m11() : 1.0;
  stroker.setWidth(std::max(4.0, 8.0 / std::max(scale, 1e-6)));
  return stroker.createStroke(path());
}

void EdgeItem::setHighlighted(bool on) {
  setPen(edgePen(m_stitch, on));
}

void EdgeItem::mousePressEvent(QGraphicsSceneMouseEvent* event) {
  m_sheet->itemClicked({m_panel, m_edge, m_stitch});
  event->accept();
}

void EdgeItem::mouseDoubleClickEvent(QGraphicsSceneMouseEvent* event) {
  m_sheet->edgeDoubleClicked(m_panel, m_edge, m_sheet->toPanel(m_panel, event->scenePos()));
  event->accept();
}

HandleItem::HandleItem(PatternSheet* sheet, int panel, int vertex, int edge, int control)
    : QGraphicsRectItem(-kHandlePixels / 2, -kHandlePixels / 2, kHandlePixels, kHandlePixels),
      m_sheet(sheet),
      m_panel(panel),
      m_vertex(vertex),
      m_edge(edge),
      m_control(control) {
  setFlags(ItemIsMovable | ItemIgnoresTransformations | ItemIsSelectable);
  setZValue(10);
  setToolTip(isVertex() ? QObject::tr("Vertex %1: drag to move, Delete to remove").arg(vertex)
                        : QObject::tr("Control point %1 of edge %2: drag to bend the edge").arg(control).arg(edge));
}

void HandleItem::paint(QPainter* painter, const QStyleOptionGraphicsItem*, QWidget*) {
  painter->setRenderHint(QPainter::Antialiasing);
  QPen pen(QColor(40, 40, 40));
  pen.setCosmetic(true);
  painter->setPen(pen);
  painter->setBrush(isSelected() ? QColor(230, 126, 34) : isVertex() ? QColor(255, 255, 255) : QColor(52, 152, 219));
  if (isVertex())
    painter->drawRect(rect());
  else
    painter->drawEllipse(rect());
}

void HandleItem::mousePressEvent(QGraphicsSceneMouseEvent* event) {
  m_pressed = pos();
  QGraphicsRectItem::mousePressEvent(event);
}

void HandleItem::mouseReleaseEvent(QGraphicsSceneMouseEvent* event) {
  QGraphicsRectItem::mouseReleaseEvent(event);
  if (pos() == m_pressed) return;
  const Eigen::Vector2d to = m_sheet->toPanel(m_panel, mapToScene(QPointF()));
  if (isVertex())
    m_sheet->vertexDragged(m_panel, m_vertex, to);
  else
    m_sheet->controlDragged(m_panel, m_edge, m_control, to);
}

MapItem::MapItem(std::vector<QPolygonF> triangles, std::vector<QColor> colors)
    : m_triangles(std::move(triangles)), m_colors(std::move(colors)) {
  for (const QPolygonF& t : m_triangles) m_bounds |= t.boundingRect();
  setAcceptedMouseButtons(Qt::NoButton);
}

void MapItem::paint(QPainter* painter, const QStyleOptionGraphicsItem*, QWidget*) {
  painter->setPen(Qt::NoPen);
  for (size_t i = 0; i < m_triangles.size(); ++i) {
    painter->setBrush(m_colors[i]);
    painter->drawPolygon(m_triangles[i]);
  }
}

}  // namespace drape::qt
