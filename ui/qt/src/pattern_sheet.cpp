#include "drape/qt/pattern_sheet.h"

#include <QFont>
#include <QGraphicsSimpleTextItem>
#include <QPen>
#include <QTimer>
#include <algorithm>
#include <cmath>

#include "drape/core/input_error.h"
#include "drape/pattern/edge_curve.h"
#include "drape/pattern/pattern_edit.h"
#include "drape/render/palette.h"
#include "pattern_sheet_items.h"

namespace drape::qt {
namespace {

constexpr double kGapMm = 60.0;    // between panels laid out side by side
constexpr double kSampleMm = 5.0;  // curves are drawn as polylines of this step

QColor displayColor(const Eigen::Vector3f& rgb) {
  return QColor::fromRgbF(std::clamp(rgb.x(), 0.0f, 1.0f), std::clamp(rgb.y(), 0.0f, 1.0f),
                          std::clamp(rgb.z(), 0.0f, 1.0f));
}

QColor panelColor(int panel) {
  // The renderer's default panel colours are linear; shown here as display colours, gamma 2.2 as in its shaders.
  const Eigen::Vector3f linear = render::defaultPanelColor(panel);
  return displayColor(linear.array().pow(1.0f / 2.2f).matrix());
}

QPainterPath arrowHead(const QPointF& tip, const QPointF& direction, double size) {
  const double n = std::hypot(direction.x(), direction.y());
  if (n <= 0.0) return {};
  const QPointF d = direction / n, side(-d.y(), d.x());
  QPainterPath path;
  path.moveTo(tip - size * d + 0.5 * size * side);
  path.lineTo(tip);
  path.lineTo(tip - size * d - 0.5 * size * side);
  return path;
}

QString panelName(const Pattern& pattern, int panel) {
  return QString::fromStdString(pattern.panels[static_cast<size_t>(panel)].name);
}

}  // namespace

QColor seamColor(int stitch) {
  const double hue = std::fmod(stitch * 137.50776405, 360.0);
  return QColor::fromHsvF(hue / 360.0, 0.8, 0.8);
}

PatternSheet::PatternSheet(QObject* parent) : QGraphicsScene(parent) {
  setBackgroundBrush(QColor(250, 250, 247));
}

double PatternSheet::millimetresPerUnit() const {
  return 1000.0 / m_pattern.unitsInMeter;
}

QPointF PatternSheet::toScene(int panel, const Eigen::Vector2d& p) const {
  const double k = millimetresPerUnit();
  const QPointF local(p.x() * k, -p.y() * k);
  if (panel < 0 || panel >= static_cast<int>(m_panels.size())) return local;
  return m_panels[static_cast<size_t>(panel)]->mapToScene(local);
}

Eigen::Vector2d PatternSheet::toPanel(int panel, const QPointF& scenePoint) const {
  const double k = millimetresPerUnit();
  QPointF local = scenePoint;
  if (panel >= 0 && panel < static_cast<int>(m_panels.size()))
    local = m_panels[static_cast<size_t>(panel)]->mapFromScene(scenePoint);
  return {local.x() / k, -local.y() / k};
}

QRectF PatternSheet::panelsRect() const {
  QRectF r;
  for (const PanelItem* p : m_panels) r |= p->sceneBoundingRect();
  return r;
}

QRectF PatternSheet::panelRect(int panel) const {
  if (panel < 0 || panel >= static_cast<int>(m_panels.size())) return {};
  return m_panels[static_cast<size_t>(panel)]->sceneBoundingRect();
}

QColor PatternSheet::edgeColor(int panel, int edge) const {
  if (panel < 0 || panel >= static_cast<int>(m_panels.size())) return {};
  for (QGraphicsItem* child : m_panels[static_cast<size_t>(panel)]->childItems())
    if (auto* e = dynamic_cast<EdgeItem*>(child); e && e->edge() == edge) return e->pen().color();
  return {};
}

int PatternSheet::mapTriangleCount() const {
  int count = 0;
  for (const PanelItem* panel : m_panels)
    for (QGraphicsItem* child : panel->childItems())
      if (auto* map = dynamic_cast<MapItem*>(child)) count += map->triangleCount();
  return count;
}

void PatternSheet::setPattern(const Pattern& pattern) {
  m_pattern = pattern;
  const auto count = static_cast<int>(pattern.panels.size());
  if (m_selection.panel >= count || m_selection.stitch >= static_cast<int>(pattern.stitches.size()) ||
      (m_selection.panel >= 0 &&
       m_selection.edge >= static_cast<int>(pattern.panels[static_cast<size_t>(m_selection.panel)].edges.size())))
    m_selection = {};
  placeNewPanels();
  scheduleRebuild();
}

void PatternSheet::scheduleRebuild() {
  // Items are rebuilt on the next turn of the event loop: an edit arrives from inside an item's mouse handler, and
  // that item must outlive its handler.
  if (m_rebuildPending) return;
  m_rebuildPending = true;
  QTimer::singleShot(0, this, [this] {
    m_rebuildPending = false;
    rebuild();
  });
}

void PatternSheet::placeNewPanels() {
  const double k = millimetresPerUnit();
  // Rows of panels, each row as wide as the widest panel or 1.5 times the side of a square of all their areas.
  std::vector<QRectF> boxes(m_pattern.panels.size());
  double area = 0.0, widest = 0.0;
  for (size_t p = 0; p < m_pattern.panels.size(); ++p) {
    QPolygonF poly;
    for (const Eigen::Vector2d& q : panelOutline(m_pattern.panels[p], kSampleMm / k))
      poly << QPointF(q.x() * k, -q.y() * k);
    boxes[p] = poly.boundingRect();
    area += boxes[p].width() * boxes[p].height();
    widest = std::max(widest, boxes[p].width());
  }
  const double rowWidth = std::max(widest, 1.5 * std::sqrt(area));
  double top = 0.0;
  bool any = false;
  for (size_t p = 0; p < m_pattern.panels.size(); ++p) {
    const auto it = m_layout.find(m_pattern.panels[p].name);
    if (it == m_layout.end()) continue;
    const QRectF placed = boxes[p].translated(it->second.origin);
    top = any ? std::max(top, placed.bottom() + kGapMm) : placed.bottom() + kGapMm;
    any = true;
  }
  double x = 0.0, rowHeight = 0.0;
  for (size_t p = 0; p < m_pattern.panels.size(); ++p) {
    if (m_layout.count(m_pattern.panels[p].name)) continue;
    if (x > 0.0 && x + boxes[p].width() > rowWidth) {
      x = 0.0;
      top += rowHeight + kGapMm;
      rowHeight = 0.0;
    }
    m_layout[m_pattern.panels[p].name] = {QPointF(x - boxes[p].left(), top - boxes[p].top()), 0.0};
    x += boxes[p].width() + kGapMm;
    rowHeight = std::max(rowHeight, boxes[p].height());
  }
}

void PatternSheet::setLayout(const SheetLayout& layout) {
  m_layout = layout;
  placeNewPanels();
  for (PanelItem* item : m_panels) {
    const PanelPlacement& place = m_layout[m_pattern.panels[static_cast<size_t>(item->panel())].name];
    item->setPos(place.origin);
    item->setRotation(place.angleDeg);
  }
}

void PatternSheet::rebuild() {
  clear();
  m_panels.clear();
  for (int p = 0; p < static_cast<int>(m_pattern.panels.size()); ++p) addPanelItems(p);
  if (m_showCheckSquare && !m_panels.empty()) {
    const QRectF r = panelsRect();
    m_checkSquare = QRectF(r.right() + kGapMm, r.top(), 100.0, 100.0);
    QPen pen(Qt::black);
    pen.setWidthF(0.3);
    addRect(m_checkSquare, pen);
    auto* label = addSimpleText(tr("10 cm check square"));
    QFont font = label->font();
    font.setPixelSize(6);
    label->setFont(font);
    label->setPos(m_checkSquare.left(), m_checkSquare.bottom() + 3.0);
  } else {
    m_checkSquare = QRectF();
  }
  refreshMap();
  applySelection();
}

void PatternSheet::addPanelItems(int p) {
  const Panel& panel = m_pattern.panels[static_cast<size_t>(p)];
  const double k = millimetresPerUnit();
  auto local = [k](const Eigen::Vector2d& q) { return QPointF(q.x() * k, -q.y() * k); };
  auto* item = new PanelItem(this, p, panelColor(p));
  QPainterPath outline;
  const std::vector<Eigen::Vector2d> points = panelOutline(panel, kSampleMm / k);
  for (size_t i = 0; i < points.size(); ++i) i ? outline.lineTo(local(points[i])) : outline.moveTo(local(points[i]));
  outline.closeSubpath();
  item->setPath(outline);
  item->setTransformOriginPoint(outline.boundingRect().center());  // a turn on the sheet keeps the panel in place
  const PanelPlacement& place = m_layout[panel.name];
  item->setPos(place.origin);
  item->setRotation(place.angleDeg);
  item->setToolTip(QString::fromStdString(panel.name));
  addItem(item);
  m_panels.push_back(item);

  for (int e = 0; e < static_cast<int>(panel.edges.size()); ++e) {
    const int segments = std::max(1, static_cast<int>(std::ceil(edgeLength(panel, e) * k / kSampleMm)));
    const std::vector<Eigen::Vector2d> samples = sampleEdge(panel, e, segments);
    QPainterPath path;
    for (size_t i = 0; i < samples.size(); ++i) i ? path.lineTo(local(samples[i])) : path.moveTo(local(samples[i]));
    const int stitch = seamOfEdge(m_pattern, p, e);
    if (stitch >= 0) {
      // The seam's direction: a chevron at the middle of the edge, pointing from its start to its end.
      const size_t mid = samples.size() / 2;
      const QPointF a = local(samples[mid - (mid > 0)]), b = local(samples[std::min(mid + 1, samples.size() - 1)]);
      path.addPath(arrowHead(local(samples[mid]), b - a, 10.0));
    }
    auto* edge = new EdgeItem(this, p, e, stitch, path);
    edge->setParentItem(item);
    edge->setToolTip(stitch >= 0
                         ? tr("'%1' edge %2, seam %3").arg(QString::fromStdString(panel.name)).arg(e).arg(stitch)
                         : tr("'%1' edge %2").arg(QString::fromStdString(panel.name)).arg(e));
  }

  const QRectF box = outline.boundingRect();
  auto* name = new QGraphicsSimpleTextItem(QString::fromStdString(panel.name), item);
  QFont font = name->font();
  font.setPixelSize(static_cast<int>(std::clamp(std::min(box.width(), box.height()) / 10.0, 8.0, 40.0)));
  name->setFont(font);
  name->setAcceptedMouseButtons(Qt::NoButton);
  name->setPos(box.center() - name->boundingRect().center());

  // The grain line (the warp): the file's, or the panel's x axis through its middle.
  QPointF g0, g1;
  if (panel.grainLine) {
    g0 = local((*panel.grainLine)[0]);
    g1 = local((*panel.grainLine)[1]);
  } else {
    g0 = QPointF(box.left() + 0.2 * box.width(), box.center().y() + 0.25 * box.height());
    g1 = QPointF(box.right() - 0.2 * box.width(), g0.y());
  }
  QPainterPath grain;
  grain.moveTo(g0);
  grain.lineTo(g1);
  grain.addPath(arrowHead(g1, g1 - g0, 12.0));
  grain.addPath(arrowHead(g0, g0 - g1, 12.0));
  QPen grainPen(QColor(90, 90, 90));
  grainPen.setCosmetic(true);
  grainPen.setWidthF(1.2);
  auto* grainItem = new QGraphicsPathItem(grain, item);
  grainItem->setPen(grainPen);
  grainItem->setAcceptedMouseButtons(Qt::NoButton);
  grainItem->setToolTip(tr("grain line"));

  QPen markPen(QColor(40, 40, 40));
  markPen.setCosmetic(true);
  markPen.setWidthF(1.2);
  const QPointF centre = box.center();
  for (const Eigen::Vector2d& n : panel.notches) {
    // A notch: a 6 mm cut from the outline towards the panel's middle.
    const QPointF at = local(n), towards = centre - at;
    const double d = std::hypot(towards.x(), towards.y());
    auto* notch = new QGraphicsLineItem(QLineF(at, d > 0 ? at + 6.0 * towards / d : at), item);
    notch->setPen(markPen);
    notch->setAcceptedMouseButtons(Qt::NoButton);
  }
  QPen internalPen = markPen;
  internalPen.setStyle(Qt::DashLine);
  for (const std::vector<Eigen::Vector2d>& line : panel.internalLines) {
    QPainterPath path;
    for (size_t i = 0; i < line.size(); ++i) i ? path.lineTo(local(line[i])) : path.moveTo(local(line[i]));
    auto* internal = new QGraphicsPathItem(path, item);
    internal->setPen(internalPen);
    internal->setAcceptedMouseButtons(Qt::NoButton);
  }
}

void PatternSheet::setCheckSquare(bool shown) {
  m_showCheckSquare = shown;
  rebuild();
}

void PatternSheet::setEditable(bool editable) {
  m_editable = editable;
  applySelection();
}

void PatternSheet::setSelection(const PatternSelection& selection) {
  if (selection == m_selection) return;
  m_selection = selection;
  applySelection();
}

void PatternSheet::applySelection() {
  const PatternSelection& s = m_selection;
  const Stitch* seam = s.stitch >= 0 && s.stitch < static_cast<int>(m_pattern.stitches.size())
                           ? &m_pattern.stitches[static_cast<size_t>(s.stitch)]
                           : nullptr;
  for (PanelItem* panel : m_panels) {
    const int p = panel->panel();
    panel->setHighlighted(p == s.panel || (seam && (seam->a.panel == p || seam->b.panel == p)));
    for (QGraphicsItem* child : panel->childItems()) {
      if (dynamic_cast<HandleItem*>(child)) {
        delete child;
        continue;
      }
      if (auto* edge = dynamic_cast<EdgeItem*>(child))
        edge->setHighlighted((seam && edge->stitch() == s.stitch) || (!seam && p == s.panel && edge->edge() == s.edge));
    }
  }
  if (!m_editable || s.panel < 0 || s.panel >= static_cast<int>(m_panels.size())) return;
  // Handles on the selected panel's outline vertices and curve control points.
  PanelItem* item = m_panels[static_cast<size_t>(s.panel)];
  const Panel& panel = m_pattern.panels[static_cast<size_t>(s.panel)];
  const double k = millimetresPerUnit();
  for (int v = 0; v < static_cast<int>(panel.vertices.size()); ++v) {
    auto* h = new HandleItem(this, s.panel, v, -1, -1);
    h->setParentItem(item);
    h->setPos(panel.vertices[static_cast<size_t>(v)].x() * k, -panel.vertices[static_cast<size_t>(v)].y() * k);
  }
  for (int e = 0; e < static_cast<int>(panel.edges.size()); ++e) {
    const PanelEdge& edge = panel.edges[static_cast<size_t>(e)];
    if (edge.curve.type != CurveType::Quadratic && edge.curve.type != CurveType::Cubic) continue;
    const Eigen::Vector2d a = panel.vertices[static_cast<size_t>(edge.start)],
                          b = panel.vertices[static_cast<size_t>(edge.end)], d = b - a, left(-d.y(), d.x());
    for (int c = 0; c < static_cast<int>(edge.curve.controls.size()); ++c) {
      const Eigen::Vector2d rel = edge.curve.controls[static_cast<size_t>(c)];
      const Eigen::Vector2d abs = a + rel.x() * d + rel.y() * left;
      auto* h = new HandleItem(this, s.panel, -1, e, c);
      h->setParentItem(item);
      h->setPos(abs.x() * k, -abs.y() * k);
    }
  }
}

void PatternSheet::setMap(SheetMap map, const Snapshot& snapshot) {
  m_map = map;
  // What the map reads, not the avatar: this runs for every shown state while a map is on.
  m_mapSnapshot = Snapshot();
  m_mapSnapshot.positions = snapshot.positions;
  m_mapSnapshot.triangles = snapshot.triangles;
  m_mapSnapshot.uvs = snapshot.uvs;
  m_mapSnapshot.trianglePanel = snapshot.trianglePanel;
  m_mapSnapshot.triangleStrain = snapshot.triangleStrain;
  m_mapSnapshot.vertexContact = snapshot.vertexContact;
  refreshMap();
}

void PatternSheet::refreshMap() {
  for (PanelItem* panel : m_panels)
    for (QGraphicsItem* child : panel->childItems())
      if (dynamic_cast<MapItem*>(child)) delete child;
  m_strainScale = 0.0;
  const Snapshot& s = m_mapSnapshot;
  const Eigen::Index nf = s.triangles.rows(), nv = s.positions.rows();
  if (m_map == SheetMap::None || nf == 0 || s.uvs.rows() != nv || s.trianglePanel.size() != nf ||
      s.trianglePanel.maxCoeff() >= static_cast<int>(m_panels.size()))
    return;
  const bool strain = m_map == SheetMap::Strain;
  if (strain && s.triangleStrain.size() != nf) return;
  if (!strain && s.vertexContact.size() != nv) return;
  if (strain) {
    double top = 0.0;
    for (Eigen::Index f = 0; f < nf; ++f)
      if (std::isfinite(s.triangleStrain(f))) top = std::max(top, s.triangleStrain(f));
    m_strainScale = top > 0.0 ? render::niceCeil(top) : 0.01;
  }
  std::vector<std::vector<QPolygonF>> triangles(m_panels.size());
  std::vector<std::vector<QColor>> colors(m_panels.size());
  for (Eigen::Index f = 0; f < nf; ++f) {
    const int p = s.trianglePanel(f);
    if (p < 0) continue;
    QPolygonF t;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Index v = s.triangles(f, c);
      t << QPointF(s.uvs(v, 0) * 1000.0, -s.uvs(v, 1) * 1000.0);  // uvs: metres in the panel's frame
    }
    QColor color;
    if (strain) {
      const double value = s.triangleStrain(f);
      color = std::isfinite(value) ? displayColor(render::strainRampColor(std::clamp(value / m_strainScale, 0.0, 1.0)))
                                   : QColor(160, 160, 160);
    } else {
      const bool touching = s.vertexContact(s.triangles(f, 0)) || s.vertexContact(s.triangles(f, 1)) ||
                            s.vertexContact(s.triangles(f, 2));
      color = touching ? QColor(230, 126, 34) : QColor(222, 222, 216);
    }
    triangles[static_cast<size_t>(p)].push_back(t);
    colors[static_cast<size_t>(p)].push_back(color);
  }
  for (size_t p = 0; p < m_panels.size(); ++p) {
    if (triangles[p].empty()) continue;
    auto* item = new MapItem(std::move(triangles[p]), std::move(colors[p]));
    item->setParentItem(m_panels[p]);
    item->setZValue(-1);  // under the edges and marks, over the panel's fill
  }
}

void PatternSheet::itemClicked(const PatternSelection& selection) {
  if (m_sewing && selection.edge >= 0) {
    if (m_sewFrom.edge < 0) {
      m_sewFrom = selection;
    } else {
      const StitchSide a{m_sewFrom.panel, m_sewFrom.edge}, b{selection.panel, selection.edge};
      m_sewing = false;
      m_sewFrom = {};
      edit([&] { return sewEdges(m_pattern, a, b); },
           tr("Sew '%1' edge %2 to '%3' edge %4")
               .arg(QString::fromStdString(m_pattern.panels[static_cast<size_t>(a.panel)].name))
               .arg(a.edge)
               .arg(QString::fromStdString(m_pattern.panels[static_cast<size_t>(b.panel)].name))
               .arg(b.edge));
    }
  }
  if (selection == m_selection) return;
  setSelection(selection);
  emit selectionChanged(m_selection);
}

void PatternSheet::startSewing() {
  m_sewing = true;
  const bool unsewnEdge = m_selection.edge >= 0 && seamOfEdge(m_pattern, m_selection.panel, m_selection.edge) < 0;
  m_sewFrom = unsewnEdge ? m_selection : PatternSelection{};
}

bool PatternSheet::rotateSelectedPanel(double degrees) {
  const int p = m_selection.panel;
  if (p < 0 || p >= static_cast<int>(m_panels.size())) return false;
  const PanelPlacement from{m_panels[static_cast<size_t>(p)]->pos(), m_panels[static_cast<size_t>(p)]->rotation()};
  PanelPlacement to = from;
  to.angleDeg = std::fmod(from.angleDeg + degrees, 360.0);
  m_panels[static_cast<size_t>(p)]->setRotation(to.angleDeg);
  const std::string& name = m_pattern.panels[static_cast<size_t>(p)].name;
  SheetLayout before = m_layout;
  before[name] = from;
  m_layout[name] = to;
  emit layoutEdited(before, m_layout, tr("Turn panel '%1' on the sheet").arg(panelName(m_pattern, p)));
  return true;
}

bool PatternSheet::deleteSelectedVertex() {
  for (QGraphicsItem* item : selectedItems())
    if (auto* handle = dynamic_cast<HandleItem*>(item); handle && handle->isVertex()) {
      vertexDeleteRequested(handle->panel(), handle->vertex());
      return true;
    }
  return false;
}

bool PatternSheet::unpickSelectedSeam() {
  if (m_selection.stitch < 0) return false;
  const int stitch = m_selection.stitch;
  edit([&] { return unpickSeam(m_pattern, stitch); }, tr("Unpick seam %1").arg(stitch));
  return true;
}

void PatternSheet::edit(const std::function<Pattern()>& make, const QString& text) {
  try {
    Pattern next = make();
    emit patternEdited(std::move(next), text);
  } catch (const InputError& e) {
    emit editRefused(QString::fromUtf8(e.what()));
  }
  // Back to the current pattern's shape until the edit is applied (setPattern) or if it is refused.
  scheduleRebuild();
}

void PatternSheet::panelDragged(int panel, const PanelPlacement& from, const PanelPlacement& to) {
  const std::string& name = m_pattern.panels[static_cast<size_t>(panel)].name;
  SheetLayout before = m_layout;
  before[name] = from;
  m_layout[name] = to;
  emit layoutEdited(before, m_layout, tr("Move panel '%1' on the sheet").arg(panelName(m_pattern, panel)));
}

void PatternSheet::vertexDragged(int panel, int vertex, const Eigen::Vector2d& to) {
  edit([&] { return moveVertex(m_pattern, panel, vertex, to); },
       tr("Move vertex %1 of '%2'").arg(vertex).arg(panelName(m_pattern, panel)));
}

void PatternSheet::controlDragged(int panel, int edge, int control, const Eigen::Vector2d& to) {
  edit([&] { return moveControlPoint(m_pattern, panel, edge, control, to); },
       tr("Bend edge %1 of '%2'").arg(edge).arg(panelName(m_pattern, panel)));
}

void PatternSheet::edgeDoubleClicked(int panel, int edge, const Eigen::Vector2d& at) {
  // The curve parameter of the edge point nearest to the click.
  const Panel& p = m_pattern.panels[static_cast<size_t>(panel)];
  double best = 0.5, bestDistance = INFINITY;
  constexpr int kSamples = 256;
  for (int i = 1; i < kSamples; ++i) {
    const double t = static_cast<double>(i) / kSamples;
    const double d = (evaluateEdge(p, edge, t) - at).norm();
    if (d < bestDistance) bestDistance = d, best = t;
  }
  edit([&] { return insertVertex(m_pattern, panel, edge, best); },
       tr("Insert a vertex in edge %1 of '%2'").arg(edge).arg(panelName(m_pattern, panel)));
}

void PatternSheet::vertexDeleteRequested(int panel, int vertex) {
  edit([&] { return deleteVertex(m_pattern, panel, vertex); },
       tr("Delete vertex %1 of '%2'").arg(vertex).arg(panelName(m_pattern, panel)));
}

}  // namespace drape::qt
