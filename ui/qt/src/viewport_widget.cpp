#include "drape/qt/viewport_widget.h"

#include <QMouseEvent>
#include <QOpenGLContext>
#include <QSurfaceFormat>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

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

ViewportWidget::~ViewportWidget() { releaseGl(); }

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
      m_renderer->upload(m_snapshot);
      m_snapshotDirty = false;
    }
    render::RenderOptions options = m_options;
    const qreal ratio = devicePixelRatioF();
    options.width = std::max(1, static_cast<int>(std::lround(width() * ratio)));
    options.height = std::max(1, static_cast<int>(std::lround(height() * ratio)));
    m_renderer->draw(m_camera, options);
    m_lastError.clear();
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

void ViewportWidget::mousePressEvent(QMouseEvent* event) {
  m_lastMouse = event->position().toPoint();
  m_dragButton = event->button();
}

void ViewportWidget::mouseMoveEvent(QMouseEvent* event) {
  if (m_dragButton == Qt::NoButton) return;
  const QPoint p = event->position().toPoint();
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

void ViewportWidget::mouseReleaseEvent(QMouseEvent*) { m_dragButton = Qt::NoButton; }

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
