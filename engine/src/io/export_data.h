#pragma once
// What the exporters write: positions, triangles, optional UVs, and named groups of triangles (one per garment
// panel, or a single group for a plain mesh). Shared by the OBJ writer and the assimp exporter.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace drape::detail {

struct ExportGroup {
  std::string name;
  std::vector<int> triangles;  // indices into ExportData::triangles
};

struct ExportData {
  const Eigen::MatrixX3d* positions = nullptr;  // |V| x 3, metres
  const Eigen::MatrixX3i* triangles = nullptr;  // |F| x 3
  const Eigen::MatrixX2d* uvs = nullptr;        // |V| x 2 or nullptr
  std::vector<ExportGroup> groups;              // every triangle in exactly one group
};

// Area-weighted vertex normals (|V| x 3, unit length; +z for a vertex no triangle with area touches).
Eigen::MatrixX3d vertexNormals(const ExportData& data);

// Wavefront OBJ text: v, vt (if uvs), vn, then "g <name>" and 1-based "f v/vt/vn" faces per group.
std::string objText(const ExportData& data);

// Writes data with assimp's exporter (formatId e.g. "glb2", "gltf2", "plyb", "stlb") and returns the bytes;
// a .gltf gets its binary buffer embedded as a base64 data URI so that it is one self-contained file.
// meshPerGroup: one assimp mesh (and node) per group, else a single mesh. Throws std::runtime_error.
std::string assimpExportBytes(const ExportData& data, const std::string& formatId, bool meshPerGroup);

}  // namespace drape::detail
