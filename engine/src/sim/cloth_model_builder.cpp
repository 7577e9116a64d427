#include "sim/cloth_model_builder.h"

#include <algorithm>
#include <optional>

#include "drape/scene/pins.h"

namespace drape {
namespace {

model::TriangleFabric toTriangleFabric(const Fabric& f) {
  model::TriangleFabric t;
  t.stretchWarp = f.stretchWarp;
  t.stretchWeft = f.stretchWeft;
  t.shear = f.shear;
  t.bendWarp = f.bendWarp;
  t.bendWeft = f.bendWeft;
  t.density = f.density;
  return t;
}

}  // namespace

model::ClothModel buildClothModel(const Scene& scene, const Garment& garment, const std::vector<int>& pinned) {
  return buildClothModel(scene, garment, pinned, simulationSettingsFrom(scene).gravity);
}

model::ClothModel buildClothModel(const Scene& scene, const Garment& garment, const std::vector<int>& pinned,
                                 double gravity) {
  model::ClothModel model;
  model.restCoords = garment.rest;
  model.triangles = garment.triangles;
  // One fabric entry per panel, expanded per triangle only when panels differ.
  std::vector<model::TriangleFabric> perPanel;
  bool uniform = true;
  for (const auto& name : garment.panelNames) {
    perPanel.push_back(toTriangleFabric(scene.fabricOfPanel(name)));
    uniform = uniform && scene.panelFabrics.count(name) == 0;
  }
  if (uniform) {
    model.fabrics = {toTriangleFabric(scene.fabric)};
  } else {
    model.fabrics.resize(garment.triangleCount());
    for (int t = 0; t < garment.triangleCount(); ++t) model.fabrics[t] = perPanel[garment.trianglePanel[t]];
  }
  model.positions.resize(3 * garment.vertexCount());
  for (int v = 0; v < garment.vertexCount(); ++v) model.positions.segment<3>(3 * v) = garment.positions.row(v);
  model.stitches = garment.stitchPairs;
  for (const GarmentEdgeStitch& e : garment.edgeStitches) model.edgeStitches.push_back({e.vertex, e.a, e.b, e.t});
  model.pinned = pinned;
  // Moving pins: each follows its pin's motion from where the garment places it.
  const std::vector<int> motionOf = pinMotionIndex(scene, garment, pinned);
  if (std::any_of(motionOf.begin(), motionOf.end(), [](int m) { return m >= 0; })) {
    std::vector<std::optional<PinMotion>> motions(pinned.size());
    std::vector<Eigen::Vector3d> initial(pinned.size());
    for (size_t k = 0; k < pinned.size(); ++k) {
      initial[k] = garment.positions.row(pinned[k]).transpose();
      if (motionOf[k] >= 0) motions[k] = scene.pins[motionOf[k]].motion;
    }
    model.pinTrajectory = [motions, initial](int k, double t) -> Eigen::Vector3d {
      return motions[k] ? motions[k]->at(initial[k], t) : initial[k];
    };
  }
  model.gravity = Eigen::Vector3d(0.0, gravity, 0.0);
  return model;
}

}  // namespace drape
