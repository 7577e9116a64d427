// Public edge geometry (drape/pattern/edge_curve.h) on top of the private CurveGeometry.
#include "drape/pattern/edge_curve.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "pattern/curve_geometry.h"

namespace drape {
namespace {

detail::CurveGeometry geometryOf(const Panel& panel, int edge) {
  if (edge < 0 || edge >= int(panel.edges.size()))
    throw std::out_of_range("panel '" + panel.name + "' has no edge " + std::to_string(edge));
  const PanelEdge& e = panel.edges[edge];
  return detail::CurveGeometry(panel.vertices.at(e.start), panel.vertices.at(e.end), e.curve);
}

}  // namespace

Eigen::Vector2d evaluateEdge(const Panel& panel, int edge, double t) {
  return geometryOf(panel, edge).point(std::clamp(t, 0.0, 1.0));
}

double edgeLength(const Panel& panel, int edge) { return geometryOf(panel, edge).length(); }

std::vector<Eigen::Vector2d> sampleEdge(const Panel& panel, int edge, int segments) {
  return geometryOf(panel, edge).sampleByArcLength(segments);
}

std::vector<Eigen::Vector2d> panelOutline(const Panel& panel, double maxSegmentLength) {
  std::vector<Eigen::Vector2d> outline;
  for (int i = 0; i < int(panel.edges.size()); ++i) {
    const detail::CurveGeometry geometry = geometryOf(panel, i);
    int segments = 1;
    if (maxSegmentLength > 0.0 && std::isfinite(maxSegmentLength))
      segments = std::max(1, int(std::ceil(geometry.length() / maxSegmentLength - 1e-9)));
    segments = std::min(segments, 100000);
    std::vector<Eigen::Vector2d> points = geometry.sampleByArcLength(segments);
    outline.insert(outline.end(), points.begin(), points.end() - 1);  // the end is the next edge's start
  }
  return outline;
}

}  // namespace drape
