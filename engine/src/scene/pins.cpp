#include "drape/scene/pins.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <string>

#include "drape/core/input_error.h"

namespace drape {

Eigen::Vector3d PinMotion::at(const Eigen::Vector3d& initial, double t) const {
  double s = 1.0;
  if (t <= start) s = 0.0;
  else if (t < end) s = (t - start) / (end - start);
  const Eigen::AngleAxisd turn(s * angle, axis);
  return center + turn * (initial - center) + s * translation;
}

std::vector<int> pinVertices(const PinSpec& pin, const Scene& scene, const Garment& garment) {
  std::vector<int> selected;
  if (pin.byRegion) {
    for (int v = 0; v < garment.vertexCount(); ++v) {
      const Eigen::Vector3d p = garment.positions.row(v).transpose();
      if ((p.array() >= pin.region.min.array()).all() && (p.array() <= pin.region.max.array()).all())
        selected.push_back(v);
    }
  } else if (!pin.vertices.empty()) {
    for (int v : pin.vertices)
      if (v >= garment.vertexCount())
        throw InputError(pin.where + ": vertex " + std::to_string(v) + " is out of range (the garment has " +
                         std::to_string(garment.vertexCount()) + " vertices with these mesh settings)");
    selected = pin.vertices;
  } else {
    const int panel = scene.pattern.panelIndex(pin.panel);
    selected = garment.edgeVertices.at(panel).at(pin.edge);
  }
  return selected;
}

std::vector<int> resolvePins(const Scene& scene, const Garment& garment) {
  std::vector<int> pinned;
  for (const PinSpec& pin : scene.pins) {
    const std::vector<int> selected = pinVertices(pin, scene, garment);
    if (selected.empty()) throw InputError(pin.where + ": selects no garment vertex");
    pinned.insert(pinned.end(), selected.begin(), selected.end());
  }
  std::sort(pinned.begin(), pinned.end());
  pinned.erase(std::unique(pinned.begin(), pinned.end()), pinned.end());
  return pinned;
}

std::vector<int> pinMotionIndex(const Scene& scene, const Garment& garment, const std::vector<int>& pinned) {
  std::vector<int> motion(pinned.size(), -1);
  for (size_t i = 0; i < scene.pins.size(); ++i) {
    if (!scene.pins[i].moving) continue;
    for (int v : pinVertices(scene.pins[i], scene, garment)) {
      auto it = std::lower_bound(pinned.begin(), pinned.end(), v);
      if (it != pinned.end() && *it == v) motion[it - pinned.begin()] = static_cast<int>(i);
    }
  }
  return motion;
}

}  // namespace drape
