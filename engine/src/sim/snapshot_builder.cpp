#include "drape/sim/snapshot_builder.h"

#include "cloth_model_builder.h"
#include "drape/geometry/strain.h"

namespace drape {

TriangleMesh mergedColliders(const Scene& scene) {
  int vertices = scene.avatar.vertexCount(), triangles = scene.avatar.triangleCount();
  for (const auto& c : scene.colliders) {
    vertices += c.mesh.vertexCount();
    triangles += c.mesh.triangleCount();
  }
  TriangleMesh merged;
  merged.vertices.resize(vertices, 3);
  merged.triangles.resize(triangles, 3);
  int v = 0, t = 0;
  auto append = [&](const TriangleMesh& m) {
    if (m.vertexCount() == 0) return;
    merged.vertices.middleRows(v, m.vertexCount()) = m.vertices;
    merged.triangles.middleRows(t, m.triangleCount()) = m.triangles.array() + v;
    v += m.vertexCount();
    t += m.triangleCount();
  };
  append(scene.avatar);
  for (const auto& c : scene.colliders) append(c.mesh);
  return merged;
}

Snapshot makeSnapshot(const Scene& scene, const Garment& garment, const Eigen::MatrixX3d& positions) {
  Snapshot s;
  s.positions = positions;
  s.triangles = garment.triangles;
  s.uvs = garment.uvs;
  s.trianglePanel = garment.trianglePanel;
  for (const auto& name : garment.panelNames) s.panelColors.push_back(scene.fabricOfPanel(name).color);
  s.triangleStrain = triangleStretch(garment.rest, positions, garment.triangles);
  s.avatar = mergedColliders(scene);
  s.contactThickness = contactThickness(scene);
  s.stage = Stage::Placed;
  return s;
}

}  // namespace drape
