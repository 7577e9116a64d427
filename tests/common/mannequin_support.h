#pragma once
// What the mannequin's tests share (tests/unit/avatar/mannequin_test.cpp and the fits of the shipped and real bodies,
// tests/slow/mannequin_fit_test.cpp): girths measured on slices of the mesh, its topology, the mannequin of a
// measurement file (made once per file), and the checks every mannequin made from measurements passes, its
// smoothness among them.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"
#include "drape/geometry/triangle_mesh.h"

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

// Where the plane through origin with unit normal n cuts the mesh: one point per crossed edge, and per triangle
// crossed on two edges the segment joining its two points (indices into points).
struct PlaneSection {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::pair<int, int>> segments;
};

inline PlaneSection planeSection(const TriangleMesh& mesh, const Eigen::Vector3d& origin, const Eigen::Vector3d& n) {
  PlaneSection section;
  std::map<std::pair<int, int>, int> pointOfEdge;
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    std::vector<int> hits;
    for (int k = 0; k < 3; ++k) {
      const int i = mesh.triangles(f, k), j = mesh.triangles(f, (k + 1) % 3);
      const Eigen::Vector3d a = mesh.vertices.row(i), b = mesh.vertices.row(j);
      const double da = (a - origin).dot(n), db = (b - origin).dot(n);
      if ((da < 0) == (db < 0)) continue;
      const auto [it, inserted] = pointOfEdge.try_emplace(std::minmax(i, j), static_cast<int>(section.points.size()));
      if (inserted) section.points.push_back(a + da / (da - db) * (b - a));
      hits.push_back(it->second);
    }
    if (hits.size() == 2) section.segments.emplace_back(hits[0], hits[1]);
  }
  return section;
}

// Connected pieces of the horizontal slice y = h: the (x, z) points where mesh edges cross the plane.
inline std::vector<std::vector<Point2>> slice(const TriangleMesh& mesh, double h) {
  const PlaneSection section = planeSection(mesh, Eigen::Vector3d(0.0, h, 0.0), Eigen::Vector3d::UnitY());
  std::vector<int> parent(section.points.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& [a, b] : section.segments) parent[find(a)] = find(b);
  std::map<int, std::vector<Point2>> pieces;
  for (int i = 0; i < static_cast<int>(section.points.size()); ++i)
    pieces[find(i)].emplace_back(section.points[i].x(), section.points[i].z());
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

// The steepest slope |dz/dy| of the front and back outlines of the side section x = x0, between heights lo and hi,
// sampled every 2 mm. Where a ledge rings the body the outline steps, far steeper than a real body's outline between
// the knees and the waist (docs/MANNEQUIN.md, "Smoothness").
inline double steepestSideOutline(const TriangleMesh& mesh, double x0, double lo, double hi) {
  const PlaneSection section = planeSection(mesh, Eigen::Vector3d(x0, 0.0, 0.0), Eigen::Vector3d::UnitX());
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> segments;  // (y, z) ends
  for (const auto& [a, b] : section.segments)
    segments.emplace_back(section.points[a].tail<2>(), section.points[b].tail<2>());
  constexpr double kStep = 0.002;
  double steepest = 0.0, lastFront = 0.0, lastBack = 0.0;
  bool haveLast = false;
  for (double y = lo; y <= hi; y += kStep) {
    double front = -1e9, back = 1e9;
    for (const auto& [a, b] : segments) {
      if ((a.x() < y) == (b.x() < y)) continue;
      const double z = a.y() + (y - a.x()) / (b.x() - a.x()) * (b.y() - a.y());
      front = std::max(front, z), back = std::min(back, z);
    }
    const bool have = front > -1e8;
    if (have && haveLast)
      steepest = std::max({steepest, std::abs(front - lastFront) / kStep, std::abs(back - lastBack) / kStep});
    haveLast = have, lastFront = front, lastBack = back;
  }
  return steepest;
}

// The +x arm's girths every centimetre along its axis, from the shoulder end to the fingertips: the hulls of
// sections perpendicular to the principal axis of the vertices beyond x = xFrom (points within 8 cm of the axis).
inline std::vector<double> armGirths(const TriangleMesh& mesh, double xFrom) {
  std::vector<Eigen::Vector3d> arm;
  for (int i = 0; i < mesh.vertexCount(); ++i)
    if (mesh.vertices(i, 0) > xFrom) arm.emplace_back(mesh.vertices.row(i));
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& p : arm) centre += p / static_cast<double>(arm.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : arm) scatter += (p - centre) * (p - centre).transpose();
  Eigen::Vector3d axis = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(2);
  if (axis.x() < 0) axis = -axis;
  double first = 1e9, last = -1e9;
  for (const auto& p : arm) first = std::min(first, (p - centre).dot(axis)), last = std::max(last, (p - centre).dot(axis));
  const Eigen::Vector3d e1 = axis.cross(Eigen::Vector3d::UnitZ()).normalized(), e2 = axis.cross(e1);
  std::vector<double> girths;
  for (double s = first + 0.01; s < last - 0.005; s += 0.01) {
    const Eigen::Vector3d origin = centre + s * axis;
    std::vector<Point2> points;
    for (const Eigen::Vector3d& p : planeSection(mesh, origin, axis).points) {
      const Eigen::Vector3d r = p - origin;
      if (r.norm() < 0.08) points.emplace_back(r.dot(e1), r.dot(e2));
    }
    girths.push_back(hullPerimeter(points));
  }
  return girths;
}

// No ledge where the torso meets the thighs, and no rings along the arms: the side outlines through the thighs
// (a third to three quarters of the hip radius out) stay smooth from 15 cm below the crotch to the waist, and the
// arm's girth falls steadily from 20 % of its length to 85 % (the hand: beyond), rising nowhere by more than 2 mm
// from one centimetre to the next.
inline void expectSmoothMannequin(const TriangleMesh& mesh, const BodyMeasurements& m) {
  const MannequinLevels levels = mannequinLevels(m);
  const double hipRadius = m.hips / (2.0 * std::numbers::pi);
  for (const double fraction : {0.3, 0.45, 0.6, 0.75}) {
    const double steepest = steepestSideOutline(mesh, fraction * hipRadius, levels.crotch - 0.15, levels.waist);
    EXPECT_LT(steepest, 2.0) << "side section at " << fraction * hipRadius << " m";
  }
  const std::vector<double> girths = armGirths(mesh, 0.5 * m.shoulderWidth + 0.05);
  ASSERT_GT(girths.size(), 30u);
  double largestRise = 0.0;
  for (size_t i = girths.size() / 5; i + 1 < girths.size() * 85 / 100; ++i)
    largestRise = std::max(largestRise, girths[i + 1] - girths[i]);
  EXPECT_LT(largestRise, 0.002) << "arm girth";
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
  expectSmoothMannequin(mesh, m);
  std::printf(
      "[mannequin] %s: %d triangles, volume %.4f m^3, height %.4f m; girths (cm) bust %.2f/%.2f "
      "underbust %.2f/%.2f waist %.2f/%.2f hips %.2f/%.2f thigh %.2f/%.2f\n",
      file.filename().string().c_str(), mesh.triangleCount(), t.volume, box.max.y(),
      100 * torsoGirth(mesh, levels.bust), 100 * m.bust, 100 * torsoGirth(mesh, levels.underbust), 100 * m.underbust,
      100 * torsoGirth(mesh, levels.waist), 100 * m.waist, 100 * torsoGirth(mesh, levels.hips), 100 * m.hips,
      100 * thighGirth(mesh, levels.crotch), 100 * m.thigh);
}

}  // namespace drape
