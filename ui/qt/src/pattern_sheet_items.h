#pragma once
// Private: the graphics items of a PatternSheet. A PanelItem is a panel's filled outline, placed on the sheet by its
// PanelPlacement; its children draw the edges, the name, the grain line, notches, internal lines, the map and the
// editing handles, all in the panel's millimetre frame with y flipped (local point = (x, -y) * mm per unit).
#include <QGraphicsPathItem>
#include <QGraphicsRectItem>
#include <QPolygonF>
#include <vector>

#include "drape/qt/pattern_sheet.h"

namespace drape::qt {

class PanelItem : public QGraphicsPathItem {
 public:
  PanelItem(PatternSheet* sheet, int panel, const QColor& color);
  int panel() const { return m_panel; }
  QColor color() const { return m_color; }
  void setHighlighted(bool on);

 protected:
  void mousePressEvent(QGraphicsSceneMouseEvent* event) override;
  void mouseReleaseEvent(QGraphicsSceneMouseEvent* event) override;

 private:
  PatternSheet* m_sheet;
  int m_panel;
  QColor m_color;
  PanelPlacement m_pressed;
};

class EdgeItem : public QGraphicsPathItem {
 public:
  EdgeItem(PatternSheet* sheet, int panel, int edge, int stitch, const QPainterPath& path);
  QPainterPath shape() const override;
  void setHighlighted(bool on);
  int edge() const { return m_edge; }
  int stitch() const { return m_stitch; }

 protected:
  void mousePressEvent(QGraphicsSceneMouseEvent* event) override;
  void mouseDoubleClickEvent(QGraphicsSceneMouseEvent* event) override;

 private:
  PatternSheet* m_sheet;
  int m_panel, m_edge, m_stitch;
};

// A square (outline vertex) or round (curve control point) handle of constant size on screen. Dragging it moves
// the point; a click selects it (PatternSheet::deleteSelectedVertex removes a selected vertex).
class HandleItem : public QGraphicsRectItem {
 public:
  HandleItem(PatternSheet* sheet, int panel, int vertex, int edge, int control);
  bool isVertex() const { return m_edge < 0; }
  int panel() const { return m_panel; }
  int vertex() const { return m_vertex; }

 protected:
  void paint(QPainter* painter, const QStyleOptionGraphicsItem* option, QWidget* widget) override;
  void mousePressEvent(QGraphicsSceneMouseEvent* event) override;
  void mouseReleaseEvent(QGraphicsSceneMouseEvent* event) override;

 private:
  PatternSheet* m_sheet;
  int m_panel, m_vertex, m_edge, m_control;
  QPointF m_pressed;
};

// Filled triangles of a map (strain or contacts) on one flat panel.
class MapItem : public QGraphicsItem {
 public:
  MapItem(std::vector<QPolygonF> triangles, std::vector<QColor> colors);
  QRectF boundingRect() const override { return m_bounds; }
  void paint(QPainter* painter, const QStyleOptionGraphicsItem* option, QWidget* widget) override;
  int triangleCount() const { return static_cast<int>(m_triangles.size()); }

 private:
  std::vector<QPolygonF> m_triangles;
  std::vector<QColor> m_colors;
  QRectF m_bounds;
};

}  // namespace drape::qt
