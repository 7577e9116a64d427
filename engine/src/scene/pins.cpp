#include "drape/scene/pins.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "drape/core/input_error.h"

namespace drape {

Eigen::Vector3d PinMotion::at(const Eigen::Vector3d& initial, double t) const {
  double s = 1.0;
  if (t <= start)
    s = 0.0;
  else if (t < end)
    s = (t - start) / (end - start);
  const Eigen::AngleAxisd turn(s * angle, axis);
  return center + turn * (initial - center) + s * translation;
}

namespace {

// A saved position and a vertex closer than this (metres) are the same point (JSON text round-off): the index
// given is kept even when another vertex sits there too (coincident vertices of two panels).
constexpr double kSamePoint = 1e-6;

std::string formatPoint(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.3f, %.3f, %.3f)", p.x(), p.y(), p.z());
  return text;
}

// Vertex entry k of a vertex pin with saved positions: the index when its vertex is at the saved position, else
// the vertex nearest to it (lowest index on a tie), when within tolerance.
int resolveSavedVertex(const PinSpec& pin, size_t k, const Garment& garment, double tolerance) {
  const Eigen::Vector3d& saved = pin.at[k];
  const int given = pin.vertices[k];
  if (given < garment.vertexCount() && (garment.positions.row(given).transpose() - saved).norm() <= kSamePoint)
    return given;
  int nearest = -1;
  double best = std::numeric_limits<double>::infinity();
  for (int v = 0; v < garment.vertexCount(); ++v) {
    const double d = (garment.positions.row(v).transpose() - saved).squaredNorm();
    if (d < best) {
      best = d;
      nearest = v;
    }
  }
  if (nearest < 0) throw InputError(pin.where + ": vertices[" + std::to_string(k) + "]: the garment has no vertex");
  const double distance = std::sqrt(best);
  if (distance > tolerance) {
    char text[160];
    std::snprintf(text, sizeof text,
                  " but the nearest garment vertex is %.1f mm away (more than %.1f mm: ", 1000.0 * distance,
                  1000.0 * tolerance);
    throw InputError(pin.where + ": vertices[" + std::to_string(k) + "] was saved at " + formatPoint(saved) + text +
                     "the pattern or its meshing changed): re-pin it");
  }
  return nearest;
}

}  // namespace

double vertexPinTolerance(const Scene& scene) {
  const double edge =
      scene.settings.has("mesh.target_edge_length") ? scene.settings.number("mesh.target_edge_length") : 0.01;
  return std::min(0.25 * edge, 0.005);
}

std::vector<int> pinVertices(const PinSpec& pin, const Scene& scene, const Garment& garment) {
  std::vector<int> selected;
  if (pin.byRegion) {
    for (int v = 0; v < garment.vertexCount(); ++v) {
      const Eigen::Vector3d p = garment.positions.row(v).transpose();
      if ((p.array() >= pin.region.min.array()).all() && (p.array() <= pin.region.max.array()).all())
        selected.push_back(v);
    }
  } else if (!pin.vertices.empty() && !pin.at.empty()) {
    // The saved positions decide; the indices are a hint (a renumbered mesh corrects them).
    if (pin.at.size() != pin.vertices.size())
      throw InputError(pin.where + ": 'at' has " + std::to_string(pin.at.size()) + " positions but 'vertices' has " +
                       std::to_string(pin.vertices.size()) + " entries");
    const double tolerance = vertexPinTolerance(scene);
    for (size_t k = 0; k < pin.vertices.size(); ++k) selected.push_back(resolveSavedVertex(pin, k, garment, tolerance));
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
