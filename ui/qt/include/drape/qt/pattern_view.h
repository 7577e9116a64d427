#pragma once
// The pattern view beside the 3D viewport: a PatternSheet in a QGraphicsView with a small tool bar.
// Mouse: the wheel zooms about the cursor, a middle or right drag pans, a left drag on a panel moves it on the sheet,
// on a handle moves an outline vertex or a curve's control point; a click selects a panel, an edge or a seam;
// a double click on an edge inserts a vertex there; Delete removes the selected vertex; R and Shift+R turn the
// selected panel on the sheet by 15 degrees. F fits the sheet to the view.
// Tool bar: Fit, Sew (the next two edges clicked), Unpick (the selected seam), the map shown on the panels and, for
// the strain map, its scale (the 3D viewport's ramp, blue at 0 to red at the scale).
#include <QGraphicsView>
#include <QWidget>

#include "drape/qt/pattern_sheet.h"

class QComboBox;
class QAction;
class QLabel;

namespace drape::qt {

class PatternView : public QGraphicsView {
  Q_OBJECT

 public:
  explicit PatternView(PatternSheet* sheet, QWidget* parent = nullptr);
  // Scales and centres the view on every panel, and keeps doing so as the view and the sheet change until the user
  // zooms or pans.
  void fitToView();

 protected:
  void wheelEvent(QWheelEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;

 private:
  void fit();
  bool m_panning = false;
  bool m_userZoomed = false;
  QPoint m_panFrom;
};

class PatternPanel : public QWidget {
  Q_OBJECT

 public:
  explicit PatternPanel(PatternSheet* sheet, QWidget* parent = nullptr);
  PatternView* view() const { return m_view; }
  QAction* sewAction() const { return m_sew; }
  QAction* unpickAction() const { return m_unpick; }
  QComboBox* mapChooser() const { return m_map; }
  // The strain map's scale ("strain 0 - 5 %"), shown while the sheet shows strain; empty otherwise.
  QString legend() const;

 signals:
  void mapChosen(drape::qt::SheetMap map);

 private:
  PatternSheet* m_sheet;
  PatternView* m_view;
  QAction* m_sew;
  QAction* m_unpick;
  QComboBox* m_map;
  QLabel* m_legend;
};

}  // namespace drape::qt
