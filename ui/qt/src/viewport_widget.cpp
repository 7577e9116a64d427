#include "drape/qt/viewport_widget.h"

#include <QMouseEvent>
#include <QPainter>
#include <QOpenGLContext>
#include <QSurfaceFormat>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "drape/qt/viewport_picking.h"
#include "drape/render/palette.h"
#include "drape/render/renderer.h"

namespace drape::qt {

ViewportWidget::ViewportWidget(QWidget* parent) : QOpenGLWidget(parent) {
  QSurfaceFormat format = QSurfaceFormat::defaultFormat();
  format.setRenderableType(QSurfaceFormat::OpenGL);
  format.setVersion(3, 3);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  setFormat(format);
  setMinimumSize(64, 64);
  m_camera = render::presetCamera(render::ViewPreset::ThreeQuarter, m_snapshot.bounds(), 1.0);
}

ViewportWidget::~ViewportWidget() {
  releaseGl();
  // QOpenGLWidget's destructor destroys the context, whose aboutToBeDestroyed must not reach this half-destroyed
  // widget.
  if (QOpenGLContext* ctx = context()) ctx->disconnect(this);
}

void ViewportWidget::releaseGl() {
  if (!m_renderer) return;
  makeCurrent();
  m_renderer.reset();
  doneCurrent();
}

void ViewportWidget::setSnapshot(const Snapshot& snapshot) {
  m_snapshot = snapshot;
  m_snapshotDirty = true;
  if (!m_hasFramed && (snapshot.positions.rows() > 0 || snapshot.avatar.vertexCount() > 0)) {
    m_hasFramed = true;
    setViewPreset(render::ViewPreset::ThreeQuarter);
  }
  update();
}

void ViewportWidget::setHighlight(std::vector<int> panels, std::vector<std::vector<int>> vertexChains) {
  m_highlightPanels = std::move(panels);
  m_highlightChains = std::move(vertexChains);
  m_snapshotDirty = true;
  update();
}

void ViewportWidget::setRenderOptions(const render::RenderOptions& options) {
  m_options = options;
  update();
}

void ViewportWidget::setCamera(const render::Camera& camera) {
  m_camera = camera;
  m_pendingPreset.reset();
  emit cameraChanged();
  update();
}

void ViewportWidget::setViewPreset(render::ViewPreset preset) {
  // The framing depends on the aspect, known for sure only once the widget has its size.
  m_pendingPreset = preset;
  m_camera = render::presetCamera(preset, m_snapshot.bounds(), aspect());
  emit cameraChanged();
  update();
}

void ViewportWidget::frameAll() {
  const Eigen::Vector3d direction = m_camera.eye - m_camera.target;
  m_camera = render::framingCamera(direction.norm() > 0 ? direction : Eigen::Vector3d::UnitZ(), m_snapshot.bounds(),
                                   aspect(), m_camera.fovYDegrees);
  emit cameraChanged();
  update();
}

double ViewportWidget::aspect() const { return height() > 0 ? double(width()) / double(height()) : 1.0; }

void ViewportWidget::initializeGL() {
  connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &ViewportWidget::releaseGl, Qt::DirectConnection);
  try {
    QOpenGLContext* ctx = context();
    m_renderer = std::make_unique<render::Renderer>(
        [ctx](const char* name) { return reinterpret_cast<void*>(ctx->getProcAddress(name)); });
    m_snapshotDirty = true;
    m_lastError.clear();
  } catch (const std::exception& e) {
    m_lastError = QString::fromStdString(e.what());
  }
}

void ViewportWidget::resizeGL(int, int) {
  if (m_pendingPreset) m_camera = render::presetCamera(*m_pendingPreset, m_snapshot.bounds(), aspect());
}

void ViewportWidget::paintGL() {
  if (!m_renderer) return;
  try {
    if (m_snapshotDirty) {
      if (m_highlightPanels.empty()) {
        m_renderer->upload(m_snapshot);
      } else {
        Snapshot shown = m_snapshot;
        const int panels = shown.trianglePanel.size() ? shown.trianglePanel.maxCoeff() + 1 : 0;
        for (int p = static_cast<int>(shown.panelColors.size()); p < panels; ++p)
          shown.panelColors.push_back(render::defaultPanelColor(p));
        const Eigen::Vector3f highlight(0.79f, 0.21f, 0.016f);  // linear RGB of the pattern view's orange
        for (int p : m_highlightPanels)
          if (p >= 0 && p < static_cast<int>(shown.panelColors.size()))
            shown.panelColors[static_cast<size_t>(p)] = 0.2f * shown.panelColors[static_cast<size_t>(p)] + 0.8f * highlight;
        m_renderer->upload(shown);
      }
      m_snapshotDirty = false;
    }
    render::RenderOptions options = m_options;
    const qreal ratio = devicePixelRatioF();
    options.width = std::max(1, static_cast<int>(std::lround(width() * ratio)));
    options.height = std::max(1, static_cast<int>(std::lround(height() * ratio)));
    m_renderer->draw(m_camera, options);
    m_lastError.clear();
    if (!m_highlightChains.empty()) {
      QPainter painter(this);
      painter.setRenderHint(QPainter::Antialiasing);
      QPen pen(QColor(230, 126, 34));
      pen.setWidthF(3.0);
      pen.setCapStyle(Qt::RoundCap);
      painter.setPen(pen);
      for (const std::vector<int>& chain : m_highlightChains) {
        QPolygonF line;
        for (int v : chain)
          if (v >= 0 && v < m_snapshot.positions.rows())
            if (const auto at = widgetPosition(m_snapshot.positions.row(v).transpose())) line << *at;
        painter.drawPolyline(line);
      }
    }
  } catch (const std::exception& e) {
    m_lastError = QString::fromStdString(e.what());
  }
}

void ViewportWidget::orbit(double dx, double dy) {
  const Eigen::Vector3d offset = m_camera.eye - m_camera.target;
  const double radius = offset.norm();
  double azimuth = std::atan2(offset.x(), offset.z());
  double elevation = std::asin(std::clamp(offset.y() / std::max(radius, 1e-12), -1.0, 1.0));
  azimuth -= dx * 0.008;
  elevation = std::clamp(elevation + dy * 0.008, -1.5, 1.5);
  m_camera.eye = m_camera.target + radius * Eigen::Vector3d(std::sin(azimuth) * std::cos(elevation),
                                                            std::sin(elevation),
                                                            std::cos(azimuth) * std::cos(elevation));
  m_camera.up = Eigen::Vector3d::UnitY();
}

void ViewportWidget::pan(double dx, double dy) {
  const Eigen::Vector3d back = (m_camera.eye - m_camera.target).normalized();
  const Eigen::Vector3d right = m_camera.up.cross(back).normalized();
  const Eigen::Vector3d up = back.cross(right);
  const double distance = (m_camera.eye - m_camera.target).norm();
  const double metresPerPixel =
      2.0 * distance * std::tan(0.5 * m_camera.fovYDegrees * 3.14159265358979 / 180.0) / std::max(height(), 1);
  const Eigen::Vector3d shift = (-dx * right + dy * up) * metresPerPixel;
  m_camera.eye += shift;
  m_camera.target += shift;
}

int ViewportWidget::garmentVertexAt(const QPointF& position) const {
  if (m_snapshot.positions.rows() == 0 || m_snapshot.triangles.rows() == 0) return -1;
  const Ray ray = rayThroughPixel(m_camera, position.x(), position.y(), width(), height());
  const auto hit = pickTriangle(ray, m_snapshot.positions, m_snapshot.triangles);
  return hit ? hit->vertex : -1;
}

std::optional<QPointF> ViewportWidget::widgetPosition(const Eigen::Vector3d& point) const {
  const auto p = projectToPixel(m_camera, point, width(), height());
  if (!p) return std::nullopt;
  return QPointF(p->x(), p->y());
}

void ViewportWidget::mousePressEvent(QMouseEvent* event) {
  m_lastMouse = event->position().toPoint();
  m_pressPosition = m_lastMouse;
  m_dragButton = event->button();
  if (!m_garmentInteraction || event->button() != Qt::LeftButton) return;
  const QPointF at = event->position();
  const Ray ray = rayThroughPixel(m_camera, at.x(), at.y(), width(), height());
  const auto hit = pickTriangle(ray, m_snapshot.positions, m_snapshot.triangles);
  if (!hit) return;  // empty space: orbit
  if (event->modifiers() & Qt::ControlModifier) {
    m_dragButton = Qt::NoButton;  // a click, not a drag
    emit pinToggleRequested(hit->vertex);
    return;
  }
  m_grabVertex = hit->vertex;
  m_grabPosition = m_snapshot.positions.row(hit->vertex).transpose();
  m_grabNormal = viewDirection(m_camera);
  // The cursor's point on the plane through the grabbed vertex: later moves shift the target by the cursor's
  // displacement on that plane, so the garment does not jump on the press.
  m_grabHit = intersectPlane(ray, m_grabPosition, m_grabNormal).value_or(m_grabPosition);
  emit dragChanged(m_grabVertex, m_grabPosition);
}

void ViewportWidget::mouseMoveEvent(QMouseEvent* event) {
  if (m_dragButton == Qt::NoButton) return;
  const QPoint p = event->position().toPoint();
  if (m_grabVertex >= 0) {
    const Ray ray = rayThroughPixel(m_camera, event->position().x(), event->position().y(), width(), height());
    if (const auto onPlane = intersectPlane(ray, m_grabPosition, m_grabNormal))
      emit dragChanged(m_grabVertex, m_grabPosition + (*onPlane - m_grabHit));
    m_lastMouse = p;
    return;
  }
  const QPoint d = p - m_lastMouse;
  m_lastMouse = p;
  if (m_dragButton == Qt::LeftButton)
    orbit(d.x(), d.y());
  else
    pan(d.x(), d.y());
  m_pendingPreset.reset();
  emit cameraChanged();
  update();
}

void ViewportWidget::mouseReleaseEvent(QMouseEvent* event) {
  m_dragButton = Qt::NoButton;
  if (m_grabVertex >= 0) {
    const int vertex = m_grabVertex;
    m_grabVertex = -1;
    emit dragChanged(-1, Eigen::Vector3d::Zero());
    if ((event->position().toPoint() - m_pressPosition).manhattanLength() < 4) emit garmentClicked(vertex);
  }
}

void ViewportWidget::mouseDoubleClickEvent(QMouseEvent*) { frameAll(); }

void ViewportWidget::wheelEvent(QWheelEvent* event) {
  const double steps = event->angleDelta().y() / 120.0;
  const double factor = std::pow(0.85, steps);
  const Eigen::Vector3d offset = m_camera.eye - m_camera.target;
  m_camera.eye = m_camera.target + offset * factor;
  m_camera.nearPlane = m_camera.farPlane = 0.0;  // derived from the new distance
  m_pendingPreset.reset();
  emit cameraChanged();
  update();
}

}  // namespace drape::qt
