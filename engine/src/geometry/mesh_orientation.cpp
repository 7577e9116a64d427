#include "drape/geometry/mesh_orientation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>
#include <unordered_map>
#include <vector>

namespace drape {
namespace {

struct EdgeFaces {
  int count = 0;
  int faces[2] = {-1, -1};
};

std::uint64_t edgeKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b)), hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

// True when face f runs from a to b (a then b in its cyclic order).
bool runs(const Eigen::Vector3i& f, int a, int b) {
  for (int k = 0; k < 3; ++k)
    if (f[k] == a && f[(k + 1) % 3] == b) return true;
  return false;
}

void turn(Eigen::MatrixX3i& triangles, int f) { std::swap(triangles(f, 1), triangles(f, 2)); }

}  // namespace

OrientationRepair orientOutward(TriangleMesh& mesh) {
  OrientationRepair repair;
  Eigen::MatrixX3i& tri = mesh.triangles;
  const Eigen::MatrixX3i before = tri;
  const int nf = mesh.triangleCount();
  std::unordered_map<std::uint64_t, EdgeFaces> edges;
  edges.reserve(static_cast<size_t>(3 * nf));
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      EdgeFaces& e = edges[edgeKey(tri(f, k), tri(f, (k + 1) % 3))];
      if (e.count < 2) e.faces[e.count] = f;
      ++e.count;
    }
  std::vector<int> part(nf, -1);
  int parts = 0;
  for (int seed = 0; seed < nf; ++seed) {
    if (part[seed] >= 0) continue;
    // Breadth first over manifold edges; each reached face is made to run against the face it was reached from.
    std::vector<int> faces{seed};
    part[seed] = parts;
    std::queue<int> open;
    open.push(seed);
    while (!open.empty()) {
      const int f = open.front();
      open.pop();
      for (int k = 0; k < 3; ++k) {
        const int a = tri(f, k), b = tri(f, (k + 1) % 3);
        const EdgeFaces& e = edges.at(edgeKey(a, b));
        if (e.count != 2) continue;
        const int g = e.faces[0] == f ? e.faces[1] : e.faces[0];
        if (part[g] >= 0) continue;
        part[g] = parts;
        if (runs(tri.row(g).transpose(), a, b)) turn(tri, g);
        faces.push_back(g);
        open.push(g);
      }
    }
    // Enclosed volume about the part's first vertex, against its area.
    const Eigen::Vector3d o = mesh.vertices.row(tri(seed, 0)).transpose();
    double volume = 0.0, area = 0.0;
    for (int f : faces) {
      const Eigen::Vector3d a = mesh.vertices.row(tri(f, 0)).transpose() - o;
      const Eigen::Vector3d b = mesh.vertices.row(tri(f, 1)).transpose() - o;
      const Eigen::Vector3d c = mesh.vertices.row(tri(f, 2)).transpose() - o;
      volume += a.dot(b.cross(c)) / 6.0;
      area += 0.5 * (b - a).cross(c - a).norm();
    }
    if (volume < -0.01 * std::pow(area, 1.5))
      for (int f : faces) turn(tri, f);
    int turned = 0;
    for (int f : faces) turned += tri(f, 1) != before(f, 1);
    repair.facesTurned += turned;
    repair.partsInsideOut += turned == static_cast<int>(faces.size());
    ++parts;
  }
  return repair;
}

}  // namespace drape
