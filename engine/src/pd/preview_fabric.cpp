#include "drape/pd/preview_fabric.h"

#include <algorithm>
#include <cmath>

namespace drape::pd {
namespace {

// Mean rest edge length over the triangles' edges (a shared edge counted once per triangle); triangles naming a
// vertex without rest coordinates are left out here, and PdSystem rejects the model for them.
double meanRestEdge(const newton::ClothModel& model) {
  const Eigen::Index vertices = model.restCoords.rows();
  double sum = 0.0;
  int edges = 0;
  for (Eigen::Index t = 0; t < model.triangles.rows(); ++t) {
    const Eigen::Vector3i tri = model.triangles.row(t);
    if ((tri.array() < 0).any() || (tri.array() >= vertices).any()) continue;
    for (int k = 0; k < 3; ++k) sum += (model.restCoords.row(tri[k]) - model.restCoords.row(tri[(k + 1) % 3])).norm();
    edges += 3;
  }
  return edges > 0 ? sum / edges : 0.0;
}

// Squared in-plane wave speed of a fabric, m^2/s^2 (0 without mass).
double waveSpeed2(const newton::TriangleFabric& f) {
  return f.density > 0.0 ? std::max(f.stretchWarp, f.stretchWeft) / f.density : 0.0;
}

}  // namespace

double courantNumber(const newton::ClothModel& model, double h) {
  const double edge = meanRestEdge(model);
  if (!(edge > 0.0)) return 0.0;
  double fastest = 0.0;
  for (const newton::TriangleFabric& f : model.fabrics) fastest = std::max(fastest, waveSpeed2(f));
  return std::sqrt(fastest) * h / edge;
}

newton::ClothModel previewFabricModel(const newton::ClothModel& model, double h, double limit) {
  newton::ClothModel out = model;
  if (!(limit > 0.0) || !(h > 0.0)) return out;
  const double edge = meanRestEdge(model);
  if (!(edge > 0.0)) return out;
  const double allowed = std::pow(limit * edge / h, 2);  // largest k / rho
  for (newton::TriangleFabric& f : out.fabrics) {
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
