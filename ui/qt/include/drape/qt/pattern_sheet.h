#pragma once
// The flat pattern as a QGraphicsScene in millimetres, y down (the pattern's y axis points up and is flipped):
// every panel's outline with its curves, its name, grain line, notches and internal lines; every seam as a pair of
// edges in the seam's own colour with an arrow along each edge's direction; optionally a snapshot's strain or
// contact map on the flat panels. Panels are laid out in rows, in pattern order, and keep their place (by name)
// when the pattern changes. The pattern view shows this scene and the 1:1 printouts draw it.
#include <QGraphicsScene>
#include <QPointF>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "drape/pattern/pattern.h"
#include "drape/sim/snapshot.h"

namespace drape::qt {

class PanelItem;

// What is selected: a panel, one of its edges, or a seam (stitch, with the edge clicked as its panel and edge).
struct PatternSelection {
  int panel = -1;
  int edge = -1;
  int stitch = -1;
  bool operator==(const PatternSelection&) const = default;
  bool empty() const { return panel < 0 && stitch < 0; }
};

enum class SheetMap { None, Strain, Contacts };

// Where a panel lies on the sheet: its frame's origin (mm, scene coordinates) and its turn (degrees, clockwise on
// screen). A layout only arranges the sheet; the garment does not depend on it.
struct PanelPlacement {
  QPointF origin;
  double angleDeg = 0.0;
  bool operator==(const PanelPlacement&) const = default;
};
using SheetLayout = std::map<std::string, PanelPlacement>;

class PatternSheet : public QGraphicsScene {
  Q_OBJECT

 public:
  explicit PatternSheet(QObject* parent = nullptr);

  // Rebuilds the items. Panels named in the current layout keep their placement, new ones go below the rest.
  void setPattern(const Pattern& pattern);
  const Pattern& pattern() const { return m_pattern; }
  bool hasPattern() const { return !m_pattern.panels.empty(); }

  // Colours the flat panels by the snapshot's triangle strain or vertex contacts (its uvs are the panels' own
  // coordinates, metres); None, or a snapshot of another meshing (different panel count), shows the plain panels.
  void setMap(SheetMap map, const Snapshot& snapshot);
  SheetMap map() const { return m_map; }
  // The strain that the top of the ramp stands for (fraction), after setMap(Strain, ...); 0 otherwise.
  double strainScale() const { return m_strainScale; }

  void setSelection(const PatternSelection& selection);
  const PatternSelection& selection() const { return m_selection; }

  const SheetLayout& layout() const { return m_layout; }
  void setLayout(const SheetLayout& layout);
  // Millimetres per file unit of the current pattern.
  double millimetresPerUnit() const;
  // Scene point of a pattern point of panel p (file units, the panel's frame), and back.
  QPointF toScene(int panel, const Eigen::Vector2d& p) const;
  Eigen::Vector2d toPanel(int panel, const QPointF& scenePoint) const;
  // Panel p's bounding rectangle on the sheet, mm (scene coordinates); empty before the items are built.
  QRectF panelRect(int panel) const;
  // The pen colour of edge e of panel p: its seam's colour, or the outline's grey when unsewn; invalid if absent.
  QColor edgeColor(int panel, int edge) const;
  // Triangles the map draws on the flat panels (0 without a map).
  int mapTriangleCount() const;
  // The panels' bounding rectangle, mm (scene coordinates), without the check square.
  QRectF panelsRect() const;
  // A 10 cm x 10 cm square with its label beside the panels, for checking a print's scale; off by default.
  void setCheckSquare(bool shown);
  QRectF checkSquareRect() const { return m_checkSquare; }
  // The outline handles of the selected panel (vertices, curve control points) follow the selection unless off.
  void setEditable(bool editable);
  bool editable() const { return m_editable; }

  // Sewing: the next two edges clicked are sewn to each other (an edge selected now counts as the first).
  void startSewing();
  bool sewing() const { return m_sewing; }
  // Unpicks the selected seam; false when no seam is selected.
  bool unpickSelectedSeam();
  // Turns the selected panel on the sheet about its middle (degrees, clockwise on screen); false when no panel is
  // selected. Undoable through layoutEdited, as a drag.
  bool rotateSelectedPanel(double degrees);
  // Deletes the outline vertex whose handle is selected; false when none is.
  bool deleteSelectedVertex();

  // Called by the items.
  void itemClicked(const PatternSelection& selection);
  void panelDragged(int panel, const PanelPlacement& from, const PanelPlacement& to);
  void vertexDragged(int panel, int vertex, const Eigen::Vector2d& to);
  void controlDragged(int panel, int edge, int control, const Eigen::Vector2d& to);
  void edgeDoubleClicked(int panel, int edge, const Eigen::Vector2d& at);
  void vertexDeleteRequested(int panel, int vertex);

 signals:
  void selectionChanged(drape::qt::PatternSelection selection);
  // A new pattern made by a gesture, and what it did ("Move vertex 3 of 'front'"); the sheet does not apply it.
  void patternEdited(drape::Pattern pattern, QString text);
  // An edit the pattern refuses (a sewn edge split, a panel left with two vertices): the refusal's message.
  void editRefused(QString message);
  void layoutEdited(drape::qt::SheetLayout from, drape::qt::SheetLayout to, QString text);

 private:
  void scheduleRebuild();
  void rebuild();
  void addPanelItems(int panel);
  void edit(const std::function<Pattern()>& make, const QString& text);
  void placeNewPanels();
  void applySelection();
  void refreshMap();

  Pattern m_pattern;
  SheetLayout m_layout;
  std::vector<PanelItem*> m_panels;
  PatternSelection m_selection;
  SheetMap m_map = SheetMap::None;
  Snapshot m_mapSnapshot;
  double m_strainScale = 0.0;
  bool m_showCheckSquare = false;
  bool m_editable = true;
  bool m_sewing = false;
  PatternSelection m_sewFrom;
  bool m_rebuildPending = false;
  QRectF m_checkSquare;
};

// The colour of seam s (display RGB): hues spaced by the golden angle, so neighbouring seams differ.
QColor seamColor(int stitch);

}  // namespace drape::qt
