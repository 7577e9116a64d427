#pragma once
// What the mannequin's tests share (tests/unit/avatar/mannequin_test.cpp and the fits of the shipped and real bodies,
// tests/slow/mannequin_fit_test.cpp): girths measured on slices of the mesh, its topology, the mannequin of a
// measurement file (made once per file), and the checks every mannequin made from measurements passes.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"

namespace drape {

using Point2 = Eigen::Vector2d;

inline double cross2(const Point2& o, const Point2& a, const Point2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Perimeter of the convex hull (gift wrapping, independent of the engine's monotone chain).
inline double hullPerimeter(const std::vector<Point2>& points) {
  if (points.size() < 3) return 0.0;
  size_t start = 0;
  for (size_t i = 1; i < points.size(); ++i)
    if (points[i].x() < points[start].x()) start = i;
  double perimeter = 0.0;
  size_t current = start;
  for (size_t guard = 0; guard <= points.size(); ++guard) {
    size_t next = (current + 1) % points.size();
    for (size_t i = 0; i < points.size(); ++i) {
      const double c = cross2(points[current], points[next], points[i]);
      if (c < 0 || (c == 0 && (points[i] - points[current]).norm() > (points[next] - points[current]).norm())) next = i;
    }
    perimeter += (points[next] - points[current]).norm();
    current = next;
    if (current == start) break;
  }
  return perimeter;
}

// Connected pieces of the horizontal slice y = h: the (x, z) points where mesh edges cross the plane.
inline std::vector<std::vector<Point2>> slice(const TriangleMesh& mesh, double h) {
  std::map<std::pair<int, int>, int> edgeId;
  std::vector<Point2> points;
  std::vector<int> parent;
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  auto crossing = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto [it, inserted] = edgeId.try_emplace(key, static_cast<int>(points.size()));
    if (inserted) {
      const Eigen::Vector3d pa = mesh.vertices.row(a), pb = mesh.vertices.row(b);
      const double t = (h - pa.y()) / (pb.y() - pa.y());
      const Eigen::Vector3d p = pa + t * (pb - pa);
      points.emplace_back(p.x(), p.z());
      parent.push_back(it->second);
    }
    return it->second;
  };
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    std::vector<int> hits;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(f, k), b = mesh.triangles(f, (k + 1) % 3);
      if ((mesh.vertices(a, 1) - h) * (mesh.vertices(b, 1) - h) < 0) hits.push_back(crossing(a, b));
    }
    if (hits.size() == 2) parent[find(hits[0])] = find(hits[1]);
  }
  std::map<int, std::vector<Point2>> pieces;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) pieces[find(i)].push_back(points[i]);
  std::vector<std::vector<Point2>> out;
  for (auto& [root, piece] : pieces) out.push_back(std::move(piece));
  return out;
}

// Girth of the torso (the piece spanning x = 0) at height h.
inline double torsoGirth(const TriangleMesh& mesh, double h) {
  double best = 0.0;
  for (const auto& piece : slice(mesh, h + 1e-7)) {
    double lo = 1e9, hi = -1e9;
    for (const auto& p : piece) lo = std::min(lo, p.x()), hi = std::max(hi, p.x());
    if (lo < 0 && hi > 0) best = std::max(best, hullPerimeter(piece));
  }
  return best;
}

// Girth of the right (+x) thigh at height h: the piece with a positive centroid nearest x = 0.
inline double thighGirth(const TriangleMesh& mesh, double h) {
  double girth = 0.0, nearest = 1e9;
  for (const auto& piece : slice(mesh, h + 1e-7)) {
    double cx = 0.0, lo = 1e9;
    for (const auto& p : piece) cx += p.x() / piece.size(), lo = std::min(lo, p.x());
    if (cx > 0 && lo > -1e-3 && cx < nearest) nearest = cx, girth = hullPerimeter(piece);
  }
  return girth;
}

struct Topology {
  bool everyEdgeTwiceOpposite = true;  // each directed edge once, and its reverse once
  int eulerCharacteristic = 0;
  int components = 0;
  double volume = 0.0;
};

inline Topology topologyOf(const TriangleMesh& mesh) {
  Topology t;
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < mesh.triangleCount(); ++f)
    for (int k = 0; k < 3; ++k) ++directed[{mesh.triangles(f, k), mesh.triangles(f, (k + 1) % 3)}];
  for (const auto& [edge, count] : directed) {
    auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) t.everyEdgeTwiceOpposite = false;
  }
  std::set<int> used;
  std::vector<int> parent(mesh.vertexCount());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    for (int k = 0; k < 3; ++k) {
      used.insert(mesh.triangles(f, k));
      parent[find(mesh.triangles(f, k))] = find(mesh.triangles(f, (k + 1) % 3));
    }
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0)), b = mesh.vertices.row(mesh.triangles(f, 1)),
                          c = mesh.vertices.row(mesh.triangles(f, 2));
    t.volume += a.dot(b.cross(c)) / 6.0;
  }
  std::set<int> roots;
  for (int v : used) roots.insert(find(v));
  t.components = static_cast<int>(roots.size());
  t.eulerCharacteristic = static_cast<int>(used.size()) - static_cast<int>(directed.size() / 2) + mesh.triangleCount();
  return t;
}

inline const TriangleMesh& mannequinFor(const std::filesystem::path& file) {
  static std::map<std::filesystem::path, TriangleMesh> cache;
  auto it = cache.find(file);
  if (it == cache.end()) it = cache.emplace(file, makeMannequin(loadBodyMeasurements(file))).first;
  return it->second;
}

inline void expectValidMannequin(const std::filesystem::path& file) {
  SCOPED_TRACE(file.filename().string());
  const BodyMeasurements m = loadBodyMeasurements(file);
  const TriangleMesh& mesh = mannequinFor(file);
  EXPECT_GE(mesh.triangleCount(), 20000);
  EXPECT_LE(mesh.triangleCount(), 60000);

  const Topology t = topologyOf(mesh);
  EXPECT_TRUE(t.everyEdgeTwiceOpposite);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.eulerCharacteristic, 2);  // a closed surface of genus 0
  // A human body is ~1 kg per litre: 40-110 kg.
  EXPECT_GT(t.volume, 0.04);
  EXPECT_LT(t.volume, 0.11);

  const BoundingBox box = boundsOf(mesh.vertices);
  EXPECT_NEAR(box.min.y(), 0.0, 1e-9);
  EXPECT_NEAR(box.max.y(), m.height, 0.01);
  // Facing +z: the toes reach further forward than the heels reach back.
  EXPECT_GT(box.max.z(), -box.min.z() - 0.05);

  const MannequinLevels levels = mannequinLevels(m);
  const double tolerance = 0.02;
  EXPECT_NEAR(torsoGirth(mesh, levels.bust), m.bust, tolerance) << "bust";
  EXPECT_NEAR(torsoGirth(mesh, levels.underbust), m.underbust, tolerance) << "underbust";
  EXPECT_NEAR(torsoGirth(mesh, levels.waist), m.waist, tolerance) << "waist";
  EXPECT_NEAR(torsoGirth(mesh, levels.hips), m.hips, tolerance) << "hips";
  EXPECT_NEAR(thighGirth(mesh, levels.crotch), m.thigh, tolerance) << "thigh";
  std::printf(
      "[mannequin] %s: %d triangles, volume %.4f m^3, height %.4f m; girths (cm) bust %.2f/%.2f "
      "underbust %.2f/%.2f waist %.2f/%.2f hips %.2f/%.2f thigh %.2f/%.2f\n",
      file.filename().string().c_str(), mesh.triangleCount(), t.volume, box.max.y(),
      100 * torsoGirth(mesh, levels.bust), 100 * m.bust, 100 * torsoGirth(mesh, levels.underbust), 100 * m.underbust,
      100 * torsoGirth(mesh, levels.waist), 100 * m.waist, 100 * torsoGirth(mesh, levels.hips), 100 * m.hips,
      100 * thighGirth(mesh, levels.crotch), 100 * m.thigh);
}

}  // namespace drape
