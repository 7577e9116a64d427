#include "drape/pd/grid_cloth.h"

#include <algorithm>

namespace drape::pd {

model::ClothModel makeGridCloth(const GridClothOptions& o) {
  model::ClothModel m;
  const int nx = std::max(o.nx, 2), ny = std::max(o.ny, 2);
  const int nv = nx * ny;
  m.restCoords.resize(nv, 2);
  m.positions.resize(3 * nv);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int v = j * nx + i;
      const double u = o.width * i / (nx - 1), w = o.height * j / (ny - 1);
      m.restCoords.row(v) << u, w;
      if (o.horizontal)
        m.positions.segment<3>(3 * v) << u - 0.5 * o.width, o.elevation, w - 0.5 * o.height;
      else
        m.positions.segment<3>(3 * v) << u - 0.5 * o.width, w + o.elevation, 0.0;
    }
  m.triangles.resize(2 * (nx - 1) * (ny - 1), 3);
  int t = 0;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      if ((i + j) % 2 == 0) {
        m.triangles.row(t++) << a, b, d;
        m.triangles.row(t++) << a, d, c;
      } else {
        m.triangles.row(t++) << a, b, c;
        m.triangles.row(t++) << b, d, c;
      }
    }
  m.fabrics.resize(1);
  if (o.pinTopCorners) m.pinned = {(ny - 1) * nx, ny * nx - 1};
  return m;
}

}  // namespace drape::pd
