#include "drape/pd/preview_fabric.h"

#include <algorithm>
#include <cmath>

#include "drape/collision/avatar_features.h"

namespace drape::pd {
namespace {

// Mean rest edge length; 0 when a triangle names a vertex without rest coordinates (PdSystem rejects that model).
double meanRestEdge(const model::ClothModel& model) {
  const Eigen::MatrixX3i& t = model.triangles;
  if (t.size() > 0 && (t.minCoeff() < 0 || t.maxCoeff() >= model.restCoords.rows())) return 0.0;
  return collision::meanEdgeLength(t, model.restCoords);
}

// Squared in-plane wave speed of a fabric, m^2/s^2 (0 without mass).
double waveSpeed2(const model::TriangleFabric& f) {
  return f.density > 0.0 ? std::max(f.stretchWarp, f.stretchWeft) / f.density : 0.0;
}

}  // namespace

double courantNumber(const model::ClothModel& model, double h) {
  const double edge = meanRestEdge(model);
  if (!(edge > 0.0)) return 0.0;
  double fastest = 0.0;
  for (const model::TriangleFabric& f : model.fabrics) fastest = std::max(fastest, waveSpeed2(f));
  return std::sqrt(fastest) * h / edge;
}

model::ClothModel previewFabricModel(const model::ClothModel& model, double h, double limit) {
  model::ClothModel out = model;
  if (!(limit > 0.0) || !(h > 0.0)) return out;
  const double edge = meanRestEdge(model);
  if (!(edge > 0.0)) return out;
  const double allowed = std::pow(limit * edge / h, 2);  // largest k / rho
  for (model::TriangleFabric& f : out.fabrics) {
    const double speed2 = waveSpeed2(f);
    if (!(speed2 > allowed)) continue;
    const double scale = allowed / speed2;
    f.stretchWarp *= scale;
    f.stretchWeft *= scale;
    f.shear *= scale;
  }
  return out;
}

}  // namespace drape::pd
