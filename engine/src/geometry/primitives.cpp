#include "drape/geometry/primitives.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace drape {
namespace {

using Triangle = Eigen::Vector3i;

// Key of an undirected edge (a, b): smaller index in the high half.
std::uint64_t edgeKey(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b));
  const auto hi = static_cast<std::uint32_t>(std::max(a, b));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

}  // namespace

TriangleMesh makeIcosphere(const Eigen::Vector3d& center, double radius, int subdivisions) {
  if (!(radius > 0.0) || subdivisions < 0 || subdivisions > 8) {
    throw std::invalid_argument("makeIcosphere: radius must be > 0 and subdivisions in [0, 8]");
  }
  // Regular icosahedron: the 12 cyclic permutations of (0, +-1, +-phi).
  const double phi = 0.5 * (1.0 + std::sqrt(5.0));
  std::vector<Eigen::Vector3d> points = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                                         {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                                         {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  for (auto& p : points) p.normalize();
  std::vector<Triangle> faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};

  for (int level = 0; level < subdivisions; ++level) {
    std::unordered_map<std::uint64_t, int> midpointOf;
    midpointOf.reserve(faces.size() * 2);
    auto midpoint = [&](int a, int b) {
      const auto [it, inserted] = midpointOf.try_emplace(edgeKey(a, b), static_cast<int>(points.size()));
      if (inserted) points.push_back((points[a] + points[b]).normalized());
      return it->second;
    };
    std::vector<Triangle> refined;
    refined.reserve(faces.size() * 4);
    for (const Triangle& f : faces) {
      const int ab = midpoint(f[0], f[1]);
      const int bc = midpoint(f[1], f[2]);
      const int ca = midpoint(f[2], f[0]);
      refined.emplace_back(f[0], ab, ca);
      refined.emplace_back(f[1], bc, ab);
      refined.emplace_back(f[2], ca, bc);
      refined.emplace_back(ab, bc, ca);
    }
    faces = std::move(refined);
  }

  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    mesh.vertices.row(static_cast<Eigen::Index>(i)) = (center + radius * points[i]).transpose();
  }
  mesh.triangles.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < faces.size(); ++i) mesh.triangles.row(static_cast<Eigen::Index>(i)) = faces[i];
  return mesh;
}

TriangleMesh makeBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  if (!(min.array() < max.array()).all()) throw std::invalid_argument("makeBox: min must be < max componentwise");
  TriangleMesh mesh;
  mesh.vertices.resize(8, 3);
  // Vertex i has x from bit 0, y from bit 1, z from bit 2 (0 = min, 1 = max).
  for (int i = 0; i < 8; ++i) {
    mesh.vertices.row(i) << (i & 1 ? max.x() : min.x()), (i & 2 ? max.y() : min.y()), (i & 4 ? max.z() : min.z());
  }
  mesh.triangles.resize(12, 3);
  mesh.triangles << 0, 2, 1, 1, 2, 3,  // z = min, normal -z
      4, 5, 6, 5, 7, 6,                // z = max, normal +z
      0, 1, 4, 1, 5, 4,                // y = min, normal -y
      2, 6, 3, 3, 6, 7,                // y = max, normal +y
      0, 4, 2, 2, 4, 6,                // x = min, normal -x
      1, 3, 5, 3, 7, 5;                // x = max, normal +x
  return mesh;
}

bool isClosedManifold(const TriangleMesh& mesh) {
  if (mesh.triangleCount() == 0) return false;
  const int n = mesh.vertexCount();
  // Per undirected edge: the number of uses in each direction (low -> high, high -> low).
  std::unordered_map<std::uint64_t, std::pair<int, int>> uses;
  uses.reserve(static_cast<std::size_t>(mesh.triangleCount()) * 2);
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    const Eigen::Vector3i t = mesh.triangles.row(f).transpose();
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= n) return false;
      const int a = t[k];
      const int b = t[(k + 1) % 3];
      if (a == b) return false;
      auto& count = uses[edgeKey(a, b)];
      (a < b ? count.first : count.second) += 1;
    }
  }
  return std::all_of(uses.begin(), uses.end(),
                     [](const auto& e) { return e.second.first == 1 && e.second.second == 1; });
}

double signedVolume(const TriangleMesh& mesh) {
  // Tetrahedra from the bounds centre rather than the origin: same sum for a closed mesh, less cancellation
  // when the mesh is far from the origin.
  const Eigen::Vector3d origin = boundsOf(mesh.vertices).center();
  double sixTimesVolume = 0.0;
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0)).transpose() - origin;
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1)).transpose() - origin;
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2)).transpose() - origin;
    sixTimesVolume += a.dot(b.cross(c));
  }
  return sixTimesVolume / 6.0;
}

}  // namespace drape
