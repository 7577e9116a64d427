#pragma once
// The 3D viewport of the desktop application: a QOpenGLWidget drawing the current snapshot through the
// same drape::render::Renderer as the headless `drape --render`, so golden images test what users see.
// Mouse: left drag orbits around the target, right or middle drag pans, the wheel zooms; double click
// frames everything.
#include <QOpenGLWidget>
#include <QPoint>
#include <memory>
#include <optional>

#include "drape/render/camera.h"
#include "drape/render/render_options.h"
#include "drape/sim/snapshot.h"

namespace drape::render {
class Renderer;
}

namespace drape::qt {

class ViewportWidget : public QOpenGLWidget {
  Q_OBJECT

 public:
  explicit ViewportWidget(QWidget* parent = nullptr);
  ~ViewportWidget() override;

  // Copies the snapshot; it is uploaded to the GPU at the next paint. The first snapshot frames itself.
  void setSnapshot(const Snapshot& snapshot);
  const Snapshot& snapshot() const { return m_snapshot; }

  // Display mode and overlays; width and height are taken from the widget (device pixels).
  void setRenderOptions(const render::RenderOptions& options);
  const render::RenderOptions& renderOptions() const { return m_options; }

  void setCamera(const render::Camera& camera);
  const render::Camera& camera() const { return m_camera; }
  // Camera preset framing the snapshot bounds for the current widget aspect.
  void setViewPreset(render::ViewPreset preset);
  // Re-frames the scene along the current viewing direction.
  void frameAll();

  // The error of the last paint (GL context too old, bad snapshot), empty when it drew.
  QString lastError() const { return m_lastError; }

 signals:
  void cameraChanged();

 protected:
  void initializeGL() override;
  void resizeGL(int width, int height) override;
  void paintGL() override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;

 private:
  void releaseGl();
  double aspect() const;
  void orbit(double dx, double dy);
  void pan(double dx, double dy);

  std::unique_ptr<render::Renderer> m_renderer;
  Snapshot m_snapshot;
  bool m_snapshotDirty = false;
  bool m_hasFramed = false;
  render::RenderOptions m_options;
  render::Camera m_camera;
  std::optional<render::ViewPreset> m_pendingPreset;
  QPoint m_lastMouse;
  Qt::MouseButton m_dragButton = Qt::NoButton;
  QString m_lastError;
};

}  // namespace drape::qt
