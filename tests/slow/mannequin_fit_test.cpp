// The parametric mannequin against the bodies it is made for: the shipped female and male measurements give closed
// meshes that fit their girths, and the mannequin made from GarmentCode's mean_all.yaml lies within a centimetre of
// the real mean_all body over torso and legs (mean_all.obj is read only here). The rest of the mannequin's tests are in
// tests/unit/avatar/mannequin_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include "drape/avatar/avatar_loader.h"
#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"
#include "drape/collision/avatar_collider.h"
#include "drape/io/mesh_export.h"
#include "mannequin_support.h"
#include "shared_data.h"

namespace drape {
namespace {

TEST(Mannequin, ShippedFemaleAndMaleMeasurementsFit) {
  expectValidMannequin(test::assetsDir() / "avatars" / "female.yaml");
  expectValidMannequin(test::assetsDir() / "avatars" / "male.yaml");
}

// A body of other proportions than the shipped ones: full hips and thighs against a narrow waist (where a ledge at
// the hips would show most), arms raised to 20 degrees below the horizontal, at a petite size. It fits its girths and
// stays smooth.
TEST(Mannequin, FullHipsAtAPetiteSizeFitAndStaySmooth) {
  BodyMeasurements m = loadBodyMeasurements(test::assetsDir() / "avatars" / "female.yaml");
  m.hips = 1.22;
  m.thigh = 0.70;
  m.waist = 0.80;
  m.armPoseAngle = 20.0;
  m = scaledBodyMeasurements(m, 0.9);
  const TriangleMesh mesh = makeMannequin(m);
  const MannequinLevels levels = mannequinLevels(m);
  EXPECT_NEAR(torsoGirth(mesh, levels.hips), m.hips, 0.02);
  EXPECT_NEAR(torsoGirth(mesh, levels.waist), m.waist, 0.02);
  EXPECT_NEAR(thighGirth(mesh, levels.crotch), m.thigh, 0.02);
  expectSmoothMannequin(mesh, m);
}

// Distance between the mannequin made from mean_all.yaml and the real mean_all body, over torso and legs.
TEST(Mannequin, MatchesTheRealMeanBodyOverTorsoAndLegs) {
  DRAPE_SHARED_FILE(yaml, "garmentcode/mean_all.yaml");
  DRAPE_SHARED_FILE(obj, "garmentcode/mean_all.obj");
  const TriangleMesh real = loadAvatar(obj);
  const TriangleMesh& ours = mannequinFor(yaml);
  const MannequinLevels levels = mannequinLevels(loadBodyMeasurements(yaml));
  expectSmoothMannequin(ours, loadBodyMeasurements(yaml));
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

}  // namespace
}  // namespace drape
