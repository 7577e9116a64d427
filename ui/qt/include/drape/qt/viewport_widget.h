#pragma once
// The 3D viewport of the desktop application: a QOpenGLWidget drawing the current snapshot through the
// same drape::render::Renderer as the headless `drape --render`, so golden images test what users see.
// Mouse: left drag orbits around the target, right or middle drag pans, the wheel zooms; double click
// frames everything. With garment interaction on (the main window turns it on), a left press ON the garment
// grabs the nearest vertex of the triangle under the cursor and dragging moves a spring target in the plane
// through that vertex facing the camera (dragChanged); Ctrl+click on the garment asks to pin or unpin the
// vertex (pinToggleRequested). A press on empty space still orbits.
#include <QOpenGLWidget>
#include <QPoint>
#include <QPointF>
#include <memory>
#include <optional>
#include <vector>

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

  // Grab-drag and Ctrl+click pinning on the garment (off by default: a bare viewport only moves the camera).
  void setGarmentInteraction(bool enabled) { m_garmentInteraction = enabled; }
  bool garmentInteraction() const { return m_garmentInteraction; }
  // The garment vertex under widget position (pixels, origin top left), or -1: the nearest vertex of the
  // nearest snapshot triangle the ray through that pixel hits.
  int garmentVertexAt(const QPointF& position) const;
  // Where a world point (metres) appears in the widget (pixels, origin top left); nullopt behind the camera.
  std::optional<QPointF> widgetPosition(const Eigen::Vector3d& point) const;
  // The vertex being dragged, -1 when none.
  int grabbedVertex() const { return m_grabVertex; }

  // Linked selection: the panels drawn in the highlight colour, and chains of garment vertices (edges, seams) drawn
  // as lines over the image.
  void setHighlight(std::vector<int> panels, std::vector<std::vector<int>> vertexChains);
  const std::vector<int>& highlightedPanels() const { return m_highlightPanels; }
  const std::vector<std::vector<int>>& highlightedChains() const { return m_highlightChains; }

  // The error of the last paint (GL context too old, bad snapshot), empty when it drew.
  QString lastError() const { return m_lastError; }

 signals:
  void cameraChanged();
  // A grabbed vertex and its spring target (metres), sent on press and on every move; vertex -1: released.
  void dragChanged(int vertex, Eigen::Vector3d target);
  // Ctrl+click on the garment: pin the vertex if it is free, unpin it if it is pinned.
  void pinToggleRequested(int vertex);
  // A left click on the garment without dragging: the vertex under the cursor (for selection).
  void garmentClicked(int vertex);

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
  bool m_garmentInteraction = false;
  int m_grabVertex = -1;
  Eigen::Vector3d m_grabPosition = Eigen::Vector3d::Zero();  // the vertex when grabbed, metres
  Eigen::Vector3d m_grabHit = Eigen::Vector3d::Zero();       // cursor ray on the drag plane at the press
  Eigen::Vector3d m_grabNormal = Eigen::Vector3d::UnitZ();   // drag plane normal (viewing direction at press)
  QString m_lastError;
  QPoint m_pressPosition;
  std::vector<int> m_highlightPanels;
  std::vector<std::vector<int>> m_highlightChains;
};

}  // namespace drape::qt
