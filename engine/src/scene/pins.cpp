#include "drape/scene/pins.h"

#include <algorithm>

#include "drape/core/input_error.h"

namespace drape {

std::vector<int> resolvePins(const Scene& scene, const Garment& garment) {
  std::vector<int> pinned;
  for (const PinSpec& pin : scene.pins) {
    const size_t before = pinned.size();
    if (pin.byRegion) {
      for (int v = 0; v < garment.vertexCount(); ++v) {
        const Eigen::Vector3d p = garment.positions.row(v).transpose();
        if ((p.array() >= pin.region.min.array()).all() && (p.array() <= pin.region.max.array()).all())
          pinned.push_back(v);
      }
    } else {
      const int panel = scene.pattern.panelIndex(pin.panel);
      const auto& vertices = garment.edgeVertices.at(panel).at(pin.edge);
      pinned.insert(pinned.end(), vertices.begin(), vertices.end());
    }
    if (pinned.size() == before) throw InputError(pin.where + ": selects no garment vertex");
  }
  std::sort(pinned.begin(), pinned.end());
  pinned.erase(std::unique(pinned.begin(), pinned.end()), pinned.end());
  return pinned;
}

}  // namespace drape
