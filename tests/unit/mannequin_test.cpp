// The parametric mannequin: topology, fitted girths measured on the mesh, and its distance to the real body
// GarmentCode's mean_all.yaml describes (the mannequin is analytic; mean_all.obj is read only here).
#include "drape/avatar/mannequin.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <set>

#include "drape/avatar/avatar_loader.h"
#include "drape/avatar/body_measurements.h"
#include "drape/collision/avatar_collider.h"
#include "drape/core/input_error.h"
#include "drape/io/mesh_export.h"
#include "shared_data.h"

namespace drape {
namespace {

using Point2 = Eigen::Vector2d;

double cross2(const Point2& o, const Point2& a, const Point2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Perimeter of the convex hull (gift wrapping, independent of the engine's monotone chain).
double hullPerimeter(const std::vector<Point2>& points) {
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
std::vector<std::vector<Point2>> slice(const TriangleMesh& mesh, double h) {
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
double torsoGirth(const TriangleMesh& mesh, double h) {
  double best = 0.0;
  for (const auto& piece : slice(mesh, h + 1e-7)) {
    double lo = 1e9, hi = -1e9;
    for (const auto& p : piece) lo = std::min(lo, p.x()), hi = std::max(hi, p.x());
    if (lo < 0 && hi > 0) best = std::max(best, hullPerimeter(piece));
  }
  return best;
}

// Girth of the right (+x) thigh at height h: the piece with a positive centroid nearest x = 0.
double thighGirth(const TriangleMesh& mesh, double h) {
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

Topology topologyOf(const TriangleMesh& mesh) {
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

const TriangleMesh& mannequinFor(const std::filesystem::path& file) {
  static std::map<std::filesystem::path, TriangleMesh> cache;
  auto it = cache.find(file);
  if (it == cache.end()) it = cache.emplace(file, makeMannequin(loadBodyMeasurements(file))).first;
  return it->second;
}

void expectValidMannequin(const std::filesystem::path& file) {
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

TEST(Mannequin, GarmentCodeMeanBodyIsClosedAndFitsItsMeasurements) {
  DRAPE_SHARED_FILE(file, "garmentcode/mean_all.yaml");
  expectValidMannequin(file);
}

TEST(Mannequin, ShippedFemaleAndMaleMeasurementsFit) {
  expectValidMannequin(test::assetsDir() / "avatars" / "female.yaml");
  expectValidMannequin(test::assetsDir() / "avatars" / "male.yaml");
}

TEST(Mannequin, ArmPoseAngleIsBelowTheHorizontal) {
  DRAPE_SHARED_FILE(file, "garmentcode/mean_all.yaml");
  BodyMeasurements m = loadBodyMeasurements(file);
  m.armPoseAngle = 0.0;  // T-pose: arms horizontal, fingertips far out at shoulder height
  MannequinOptions coarse;
  coarse.facetSize = 0.03;
  coarse.facetDistance = 0.005;
  const TriangleMesh tpose = makeMannequin(m, coarse);
  const BoundingBox box = boundsOf(tpose.vertices);
  const double reach = 0.5 * m.shoulderWidth + m.armLength;
  EXPECT_GT(box.max.x(), reach);
  EXPECT_LT(box.max.x(), reach + 0.25);
  // The extreme-x vertex sits at about shoulder-joint height.
  Eigen::Index tip = 0;
  tpose.vertices.col(0).maxCoeff(&tip);
  EXPECT_NEAR(tpose.vertices(tip, 1), mannequinLevels(m).neckBase - 0.09, 0.06);

  // mean_all's own arm: 45.5 degrees below the horizontal, so at wrist height the reach is ~cos(45.5) arm.
  const TriangleMesh& apose = mannequinFor(file);
  EXPECT_LT(boundsOf(apose.vertices).max.x(), 0.5 * m.shoulderWidth + std::cos(0.8) * m.armLength + 0.2);
}

// CGAL hands the surface's facets over in an order that follows memory addresses; the mannequin's own order is
// canonical, so that the same measurements give the same file in every run (CliMakeAvatar checks two processes).
TEST(Mannequin, MeshIsInCanonicalOrder) {
  const BodyMeasurements m = loadBodyMeasurements(test::assetsDir() / "avatars" / "female.yaml");
  MannequinOptions coarse;
  coarse.facetSize = 0.03;
  coarse.facetDistance = 0.005;
  const TriangleMesh a = makeMannequin(m, coarse);
  ASSERT_GT(a.vertices.rows(), 100);
  for (Eigen::Index i = 1; i < a.vertices.rows(); ++i) {
    const Eigen::RowVector3d p = a.vertices.row(i - 1), q = a.vertices.row(i);
    ASSERT_TRUE(std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3)) << "vertex " << i;
  }
  for (Eigen::Index f = 0; f < a.triangles.rows(); ++f) {
    ASSERT_LT(a.triangles(f, 0), a.triangles(f, 1)) << "triangle " << f;
    ASSERT_LT(a.triangles(f, 0), a.triangles(f, 2)) << "triangle " << f;
    if (f > 0) {
      const Eigen::RowVector3i s = a.triangles.row(f - 1), t = a.triangles.row(f);
      ASSERT_TRUE(std::lexicographical_compare(s.data(), s.data() + 3, t.data(), t.data() + 3)) << "triangle " << f;
    }
  }
}

TEST(Mannequin, InconsistentLandmarksAreInputErrors) {
  DRAPE_SHARED_FILE(file, "garmentcode/mean_all.yaml");
  BodyMeasurements m = loadBodyMeasurements(file);
  m.waistLine = 1.5;  // waist below the floor
  EXPECT_THROW(mannequinLevels(m), InputError);
}

// Without the optional landmark keys the levels are fixed fractions of the input's own height, and the girths
// still fit.
TEST(Mannequin, MissingLandmarksFollowTheHeight) {
  BodyMeasurements m = loadBodyMeasurements(test::assetsDir() / "avatars" / "male.yaml");
  m.headLength.reset();
  m.waistLine.reset();
  m.hipsLine.reset();
  m.crotchHipDiff.reset();
  m.vertBustLine.reset();
  m.height = 1.90;
  const MannequinLevels levels = mannequinLevels(m);
  EXPECT_NEAR(levels.top, 1.90, 1e-12);
  EXPECT_NEAR(levels.neckBase, 1.90 * (1 - 0.150), 1e-9);
  EXPECT_NEAR(levels.waist, 1.90 * (1 - 0.150 - 0.220), 1e-9);
  EXPECT_NEAR(levels.hips, 1.90 * (1 - 0.150 - 0.220 - 0.130), 1e-9);
  EXPECT_NEAR(levels.crotch, 1.90 * (1 - 0.150 - 0.220 - 0.130 - 0.050), 1e-9);
  EXPECT_NEAR(levels.bust, 1.90 * (1 - 0.150 - 0.125), 1e-9);
  EXPECT_NEAR(levels.underbust, levels.bust - 0.45 * (levels.bust - levels.waist), 1e-9);

  MannequinOptions coarse;
  coarse.facetSize = 0.015;
  const TriangleMesh mesh = makeMannequin(m, coarse);
  EXPECT_NEAR(boundsOf(mesh.vertices).max.y(), 1.90, 0.01);
  EXPECT_NEAR(torsoGirth(mesh, levels.bust), m.bust, 0.02);
  EXPECT_NEAR(torsoGirth(mesh, levels.waist), m.waist, 0.02);
  EXPECT_NEAR(torsoGirth(mesh, levels.hips), m.hips, 0.02);
  EXPECT_NEAR(thighGirth(mesh, levels.crotch), m.thigh, 0.02);
}

// Distance between the mannequin made from mean_all.yaml and the real mean_all body, over torso and legs.
TEST(Mannequin, MatchesTheRealMeanBodyOverTorsoAndLegs) {
  DRAPE_SHARED_FILE(yaml, "garmentcode/mean_all.yaml");
  DRAPE_SHARED_FILE(obj, "garmentcode/mean_all.obj");
  const TriangleMesh real = loadAvatar(obj);
  const TriangleMesh& ours = mannequinFor(yaml);
  const MannequinLevels levels = mannequinLevels(loadBodyMeasurements(yaml));
  std::filesystem::create_directories(test::testOutputDir() / "mannequin");
  exportMesh(ours, test::testOutputDir() / "mannequin" / "mean_all_mannequin.obj");  // for inspection
  // Torso and legs: below the armpits, inside the shoulder width (the arms of the A-pose lie outside).
  const double top = levels.bust;
  auto inRegion = [&](const Eigen::Vector3d& p) { return p.y() < top && std::abs(p.x()) < 0.195; };
  auto distances = [&](const TriangleMesh& from, const TriangleMesh& to) {
    const collision::AvatarCollider collider(to);
    std::vector<double> d;
    for (int i = 0; i < from.vertexCount(); ++i) {
      const Eigen::Vector3d p = from.vertices.row(i);
      if (inRegion(p)) d.push_back(std::abs(collider.signedDistance(p)));
    }
    std::sort(d.begin(), d.end());
    return d;
  };
  auto mean = [](const std::vector<double>& d) { return std::accumulate(d.begin(), d.end(), 0.0) / d.size(); };
  auto p95 = [](const std::vector<double>& d) { return d[static_cast<size_t>(0.95 * (d.size() - 1))]; };
  // Where the differences are: mean signed distance of the real body's vertices to ours (> 0: the real body
  // lies outside ours) and mean |distance|, per 10 cm band of height.
  {
    const collision::AvatarCollider collider(ours);
    std::map<int, std::pair<double, std::pair<double, int>>> bands;
    for (int i = 0; i < real.vertexCount(); ++i) {
      const Eigen::Vector3d p = real.vertices.row(i);
      if (!inRegion(p)) continue;
      const double d = collider.signedDistance(p);
      auto& band = bands[static_cast<int>(std::floor(p.y() * 10.0))];
      band.first += d;
      band.second.first += std::abs(d);
      ++band.second.second;
    }
    for (const auto& [band, sums] : bands)
      std::printf("[mannequin] band %.1f-%.1f m: signed %+.2f cm, |d| %.2f cm (%d vertices)\n", band / 10.0,
                  (band + 1) / 10.0, 100 * sums.first / sums.second.second,
                  100 * sums.second.first / sums.second.second, sums.second.second);
  }
  const std::vector<double> realToOurs = distances(real, ours);
  const std::vector<double> oursToReal = distances(ours, real);
  ASSERT_GT(realToOurs.size(), 5000u);
  ASSERT_GT(oursToReal.size(), 5000u);
  std::printf(
      "[mannequin] mean_all torso+legs: real->ours mean %.2f cm, p95 %.2f cm, max %.2f cm; ours->real mean "
      "%.2f cm, p95 %.2f cm, max %.2f cm\n",
      100 * mean(realToOurs), 100 * p95(realToOurs), 100 * realToOurs.back(), 100 * mean(oursToReal),
      100 * p95(oursToReal), 100 * oursToReal.back());
  // The mannequin is an analytic body that never reads mean_all.obj, so this is a genuine comparison.
  // Achieved (default options): means 0.70 / 0.71 cm, 95th percentiles 1.73 / 1.85 cm (issue target: mean
  // under 2 cm); the bounds leave ~30% margin for meshing noise.
  EXPECT_LT(mean(realToOurs), 0.01);
  EXPECT_LT(mean(oursToReal), 0.01);
  EXPECT_LT(p95(realToOurs), 0.025);
  EXPECT_LT(p95(oursToReal), 0.025);
}

// Writes assets/avatars/{female,male}.obj. Run with --gtest_also_run_disabled_tests.
TEST(Mannequin, DISABLED_WriteShippedAvatars) {
  for (const char* name : {"female", "male"}) {
    const auto dir = test::assetsDir() / "avatars";
    const auto yaml = dir / (std::string(name) + ".yaml");
    exportMesh(mannequinFor(yaml), dir / (std::string(name) + ".obj"));
  }
}

}  // namespace
}  // namespace drape
