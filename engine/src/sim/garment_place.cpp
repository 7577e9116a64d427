#include "sim/garment_place.h"

#include <cstdio>

namespace drape {

std::string panelOf(const Garment& garment, int panel) {
  if (panel < 0 || panel >= static_cast<int>(garment.panelNames.size())) return "";
  return " of panel '" + garment.panelNames[panel] + "'";
}

std::string atPoint(const Eigen::Vector3d& p) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, " at (%.3f, %.3f, %.3f) m", p.x(), p.y(), p.z());
  return buffer;
}

std::string vertexPlace(const Garment& garment, const Eigen::MatrixX3d& x, int v) {
  const int panel = v < garment.vertexPanel.size() ? garment.vertexPanel[v] : -1;
  return "vertex " + std::to_string(v) + panelOf(garment, panel) + atPoint(x.row(v).transpose());
}

std::string triangleName(const Garment& garment, int t) {
  const int panel = t < garment.trianglePanel.size() ? garment.trianglePanel[t] : -1;
  return "triangle " + std::to_string(t) + panelOf(garment, panel);
}

Eigen::Vector3d triangleCentre(const Garment& garment, const Eigen::MatrixX3d& x, int t) {
  return (x.row(garment.triangles(t, 0)) + x.row(garment.triangles(t, 1)) + x.row(garment.triangles(t, 2)))
             .transpose() /
         3.0;
}

}  // namespace drape
