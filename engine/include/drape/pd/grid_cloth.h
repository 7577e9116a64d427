#pragma once
// A rectangular cloth for tests and benchmarks (the paper's hanging tablecloth, Fig. 12/13): a regular grid in
// the material frame, placed vertically (x right, y up) or horizontally (x, z) in world space.
#include "drape/model/cloth_model.h"

namespace drape::pd {

struct GridClothOptions {
  int nx = 20;                 // vertices along the warp (x)
  int ny = 20;                 // vertices along the weft (y)
  double width = 1.0;          // metres
  double height = 1.0;         // metres
  bool horizontal = false;     // true: lies in the x-z plane at y = elevation
  double elevation = 0.0;      // metres
  bool pinTopCorners = true;   // pins the two corners of the last row (top when vertical)
};

// Vertex (i, j) has index j * nx + i and rest coords (i width / (nx - 1), j height / (ny - 1)).
model::ClothModel makeGridCloth(const GridClothOptions& options);

}  // namespace drape::pd
