#pragma once
// CPU-side vertex data of a snapshot, as the shaders read it (shaders/mesh.vert).
#include <vector>

#include "drape/sim/snapshot.h"

namespace drape::render {

// Per triangle corner, 19 floats: position (3, metres), smooth normal (3), barycentric corner (3),
// panel colour (3, linear), domain colour (3, linear), strain (1; kNoStrain when absent), contact (1),
// pattern coordinates (2, metres; 0 without uvs).
inline constexpr int kGarmentFloats = 19;
inline constexpr float kNoStrain = -1e9f;

struct GarmentVertices {
  std::vector<float> data;  // 3 |F| corners x kGarmentFloats
  bool hasStrain = false;
  double strainMaximum = 0.0;  // largest finite triangle strain (0 without strain)
};

// Validates the snapshot (indices in range, optional arrays empty or of the right length) and expands the
// garment to one vertex per triangle corner. Throws std::invalid_argument naming the bad element.
GarmentVertices buildGarmentVertices(const Snapshot& snapshot);

// Avatar: per vertex position (3) + smooth normal (3), and the triangle indices. Validates indices.
struct AvatarVertices {
  std::vector<float> data;
  std::vector<unsigned> indices;
};
AvatarVertices buildAvatarVertices(const TriangleMesh& avatar);

// Area-weighted vertex normals (|V| x 3, unit; +y where all adjacent triangles are degenerate).
Eigen::MatrixX3f vertexNormals(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& triangles);

}  // namespace drape::render
