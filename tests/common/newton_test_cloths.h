// Small cloth models shared by the Newton solver and contact tests.
#pragma once

#include <random>

#include "drape/model/cloth_model.h"

namespace drape::newton {

// n x n grid of spacing d, anisotropic fabric, random 3D perturbation of amplitude `noise` * d.
inline drape::model::ClothModel gridCloth(int n, double d, double noise, unsigned seed) {
  drape::model::ClothModel m;
  m.restCoords.resize(n * n, 2);
  m.positions.resize(3 * n * n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-noise * d, noise * d);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.restCoords.row(i * n + j) << j * d, i * d;
      m.positions.segment<3>(3 * (i * n + j)) << 1.05 * j * d + u(rng), i * d + u(rng), u(rng);
    }
  m.triangles.resize(2 * (n - 1) * (n - 1), 3);
  int t = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      int a = i * n + j, b = a + 1, c = a + n, e = c + 1;
      m.triangles.row(t++) << a, b, e;
      m.triangles.row(t++) << a, e, c;
    }
  drape::model::TriangleFabric f;
  f.stretchWarp = 5000.0;
  f.stretchWeft = 3000.0;
  f.shear = 200.0;
  f.bendWarp = 5e-6;
  f.bendWeft = 2e-6;
  m.fabrics = {f};
  return m;
}

// 1 m x 1 m gridCloth of n x n vertices hanging from its two top corners.
inline drape::model::ClothModel hangingGridCloth(int n, double noise, unsigned seed) {
  drape::model::ClothModel m = gridCloth(n, 1.0 / (n - 1), noise, seed);
  m.pinned = {n * (n - 1), n * n - 1};
  return m;
}

// Vertical panel of nx x ny vertices, width x height metres, bottom-left corner at `origin`, appended to m; rest
// coords from 0.
inline void appendGridPanel(drape::model::ClothModel& m, int nx, int ny, double width, double height, const Eigen::Vector3d& origin) {
  const int base = m.numVertices();
  m.restCoords.conservativeResize(base + nx * ny, 2);
  m.positions.conservativeResize(3 * (base + nx * ny));
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector2d r(width * i / (nx - 1), height * j / (ny - 1));
      m.restCoords.row(base + j * nx + i) = r.transpose();
      m.positions.segment<3>(3 * (base + j * nx + i)) = origin + Eigen::Vector3d(r.x(), r.y(), 0.0);
    }
  int t = static_cast<int>(m.triangles.rows());
  m.triangles.conservativeResize(t + 2 * (nx - 1) * (ny - 1), 3);
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = base + j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      m.triangles.row(t++) << a, b, d;
      m.triangles.row(t++) << a, d, c;
    }
}

}  // namespace drape::newton
