#include "sim/exploded_state.h"

#include <cmath>
#include <cstdio>

#include "sim/garment_place.h"

namespace drape {

std::string explodedReason(const Garment& garment, const Eigen::MatrixX3d& x, const Eigen::VectorXd& stretch,
                           const Eigen::AlignedBox3d& sceneBox, double gravity, double time) {
  char buffer[160];
  for (Eigen::Index t = 0; t < stretch.size(); ++t) {
    if (!(stretch[t] > kExplodedStrain)) continue;
    std::snprintf(buffer, sizeof buffer, "the garment exploded: %s stretched %.0f %% (no fabric holds past %.0f %%)",
                  triangleName(garment, static_cast<int>(t)).c_str(), 100.0 * stretch[t], 100.0 * kExplodedStrain);
    return buffer + atPoint(triangleCentre(garment, x, static_cast<int>(t)));
  }
  if (sceneBox.isEmpty()) return "";
  const double size = std::max(sceneBox.diagonal().norm(), 1e-3);
  const double reach = kExplodedSceneSizes * size + 0.5 * std::abs(gravity) * time * time;
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const Eigen::Vector3d p = x.row(v).transpose();
    const double away = sceneBox.exteriorDistance(p);
    if (!(away > reach)) continue;
    std::snprintf(buffer, sizeof buffer, "the garment exploded: %.3g m outside the scene (%.2f m across): ", away,
                  size);
    return buffer + vertexPlace(garment, x, static_cast<int>(v));
  }
  return "";
}

}  // namespace drape
