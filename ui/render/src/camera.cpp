#include "drape/render/camera.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace drape::render {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFrameMargin = 0.90;  // the framed bounds fill at most 90% of the image width or height

Eigen::Vector3d presetDirection(ViewPreset preset) {
  const double elevation = 8.0 * kPi / 180.0;  // a slightly raised eye reads the shape better
  switch (preset) {
    case ViewPreset::Front: return {0.0, std::sin(elevation), std::cos(elevation)};
    case ViewPreset::Back: return {0.0, std::sin(elevation), -std::cos(elevation)};
    case ViewPreset::Left: return {std::cos(elevation), std::sin(elevation), 0.0};
    case ViewPreset::Right: return {-std::cos(elevation), std::sin(elevation), 0.0};
    case ViewPreset::ThreeQuarter: {
      const double azimuth = 35.0 * kPi / 180.0, up = 18.0 * kPi / 180.0;
      return {std::sin(azimuth) * std::cos(up), std::sin(up), std::cos(azimuth) * std::cos(up)};
    }
  }
  return {0.0, 0.0, 1.0};
}

}  // namespace

Eigen::Matrix4f Camera::viewMatrix() const {
  const Eigen::Vector3d f = (target - eye).normalized();
  Eigen::Vector3d s = f.cross(up);
  if (s.norm() < 1e-12) s = f.cross(Eigen::Vector3d::UnitZ());
  s.normalize();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m.cast<float>();
}

Eigen::Matrix4f Camera::projectionMatrix(double aspect) const {
  const double distance = std::max((target - eye).norm(), 1e-6);
  const double n = nearPlane > 0.0 ? nearPlane : distance * 0.05;
  const double f = farPlane > n ? farPlane : distance * 20.0;
  const double t = 1.0 / std::tan(0.5 * fovYDegrees * kPi / 180.0);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = (f + n) / (n - f);
  p(2, 3) = 2.0 * f * n / (n - f);
  p(3, 2) = -1.0;
  return p.cast<float>();
}

std::string_view viewPresetName(ViewPreset preset) {
  switch (preset) {
    case ViewPreset::Front: return "front";
    case ViewPreset::Back: return "back";
    case ViewPreset::Left: return "left";
    case ViewPreset::Right: return "right";
    case ViewPreset::ThreeQuarter: return "three-quarter";
  }
  return "front";
}

std::optional<ViewPreset> parseViewPreset(std::string_view name) {
  for (ViewPreset p : kAllViewPresets)
    if (viewPresetName(p) == name) return p;
  return std::nullopt;
}

Camera framingCamera(const Eigen::Vector3d& direction, const BoundingBox& bounds, double aspect,
                     double fovYDegrees) {
  BoundingBox b = bounds;
  if (b.empty()) {
    b.extend(Eigen::Vector3d::Constant(-0.5));
    b.extend(Eigen::Vector3d::Constant(0.5));
  }
  const Eigen::Vector3d center = b.center();
  const Eigen::Vector3d back = direction.normalized();  // from target towards the eye
  Eigen::Vector3d right = Eigen::Vector3d::UnitY().cross(back);
  if (right.norm() < 1e-9) right = Eigen::Vector3d::UnitX();
  right.normalize();
  const Eigen::Vector3d up = back.cross(right);

  const double tanY = std::tan(0.5 * fovYDegrees * kPi / 180.0) * kFrameMargin;
  const double tanX = tanY * std::max(aspect, 1e-3);
  // Smallest distance d with every corner inside the frustum: |x| <= (d - z) tanX and |y| <= (d - z) tanY.
  double distance = 0.0, radius = 0.0;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d corner((i & 1) ? b.max.x() : b.min.x(), (i & 2) ? b.max.y() : b.min.y(),
                                 (i & 4) ? b.max.z() : b.min.z());
    const Eigen::Vector3d p = corner - center;
    const double z = p.dot(back);
    distance = std::max({distance, std::abs(p.dot(right)) / tanX + z, std::abs(p.dot(up)) / tanY + z});
    radius = std::max(radius, p.norm());
  }
  radius = std::max(radius, 1e-3);
  distance = std::max(distance, 1.5 * radius);

  Camera camera;
  camera.target = center;
  camera.eye = center + distance * back;
  camera.up = up;
  camera.fovYDegrees = fovYDegrees;
  camera.nearPlane = std::max(distance - 2.0 * radius, distance * 0.02);
  camera.farPlane = distance + 6.0 * radius;  // room for the ground plane behind the scene
  return camera;
}

Camera presetCamera(ViewPreset preset, const BoundingBox& bounds, double aspect, double fovYDegrees) {
  return framingCamera(presetDirection(preset), bounds, aspect, fovYDegrees);
}

}  // namespace drape::render
