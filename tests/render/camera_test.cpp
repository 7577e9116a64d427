// Camera presets frame the scene bounds: every corner projects inside the image, the bounds fill a good part
// of it, and each preset looks from the documented side.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "drape/render/camera.h"

namespace drape::test {
namespace {

using render::ViewPreset;

BoundingBox box(Eigen::Vector3d min, Eigen::Vector3d max) {
  BoundingBox b;
  b.extend(min);
  b.extend(max);
  return b;
}

// Normalised device coordinates of p.
Eigen::Vector3d project(const render::Camera& camera, double aspect, const Eigen::Vector3d& p) {
  const Eigen::Vector4f clip = camera.projectionMatrix(aspect) * camera.viewMatrix() * p.cast<float>().homogeneous();
  return (clip.head<3>() / clip.w()).cast<double>();
}

TEST(CameraTest, PresetsFrameAllCornersTightly) {
  const BoundingBox bounds = box({-0.3, 0.0, -0.2}, {0.3, 1.8, 0.25});
  for (double aspect : {1.0, 16.0 / 9.0, 0.6})
    for (ViewPreset preset : render::kAllViewPresets) {
      const render::Camera camera = render::presetCamera(preset, bounds, aspect);
      double extentX = 0.0, extentY = 0.0;
      for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3d corner((i & 1) ? bounds.max.x() : bounds.min.x(),
                                     (i & 2) ? bounds.max.y() : bounds.min.y(),
                                     (i & 4) ? bounds.max.z() : bounds.min.z());
        const Eigen::Vector3d ndc = project(camera, aspect, corner);
        EXPECT_LE(std::abs(ndc.x()), 0.9001) << render::viewPresetName(preset) << " aspect " << aspect;
        EXPECT_LE(std::abs(ndc.y()), 0.9001) << render::viewPresetName(preset) << " aspect " << aspect;
        EXPECT_GT(ndc.z(), -1.0);
        EXPECT_LT(ndc.z(), 1.0);
        extentX = std::max(extentX, std::abs(ndc.x()));
        extentY = std::max(extentY, std::abs(ndc.y()));
      }
      // Tight: some corner touches the 90% frame in x or y.
      EXPECT_NEAR(std::max(extentX, extentY), 0.9, 1e-3) << render::viewPresetName(preset);
    }
}

TEST(CameraTest, PresetDirectionsFollowTheConvention) {
  const BoundingBox bounds = box({-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5});
  const Eigen::Vector3d c = bounds.center();
  auto dir = [&](ViewPreset p) { return Eigen::Vector3d((render::presetCamera(p, bounds, 1.0).eye - c).normalized()); };
  EXPECT_GT(dir(ViewPreset::Front).z(), 0.95);
  EXPECT_LT(dir(ViewPreset::Back).z(), -0.95);
  EXPECT_GT(dir(ViewPreset::Left).x(), 0.95);   // the wearer's left is +x when facing +z
  EXPECT_LT(dir(ViewPreset::Right).x(), -0.95);
  const Eigen::Vector3d q = dir(ViewPreset::ThreeQuarter);
  EXPECT_GT(q.x(), 0.3);
  EXPECT_GT(q.z(), 0.6);
  EXPECT_GT(q.y(), 0.1);
  for (ViewPreset p : render::kAllViewPresets) {
    const render::Camera camera = render::presetCamera(p, bounds, 1.0);
    EXPECT_TRUE(camera.target.isApprox(c));
    EXPECT_GT(camera.up.y(), 0.9);  // y stays up on screen
  }
}

TEST(CameraTest, PresetsAreDeterministicAndNamed) {
  const BoundingBox bounds = box({-1, -1, -1}, {1, 2, 1});
  for (ViewPreset p : render::kAllViewPresets) {
    EXPECT_EQ(render::parseViewPreset(render::viewPresetName(p)), p);
    const render::Camera a = render::presetCamera(p, bounds, 1.3), b = render::presetCamera(p, bounds, 1.3);
    EXPECT_EQ(a.eye, b.eye);
  }
  EXPECT_FALSE(render::parseViewPreset("top").has_value());
  EXPECT_EQ(render::parseViewPreset("three-quarter"), ViewPreset::ThreeQuarter);
}

TEST(CameraTest, EmptyBoundsStillGiveAUsableCamera) {
  const render::Camera camera = render::presetCamera(ViewPreset::Front, BoundingBox{}, 1.0);
  EXPECT_TRUE(camera.eye.allFinite());
  EXPECT_GT((camera.eye - camera.target).norm(), 0.5);
}

TEST(CameraTest, ViewMatrixMapsEyeToOriginAndTargetToNegativeZ) {
  render::Camera camera;
  camera.eye = {1.0, 2.0, 3.0};
  camera.target = {1.0, 2.0, 0.0};
  const Eigen::Matrix4f view = camera.viewMatrix();
  EXPECT_TRUE((view * Eigen::Vector4f(1, 2, 3, 1)).head<3>().isZero(1e-6f));
  EXPECT_TRUE((view * Eigen::Vector4f(1, 2, 0, 1)).head<3>().isApprox(Eigen::Vector3f(0, 0, -3), 1e-6f));
}

}  // namespace
}  // namespace drape::test
