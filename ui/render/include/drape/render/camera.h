#pragma once
// Cameras: explicit (eye, target, up, vertical field of view) or a preset framing the scene bounds.
// World convention: y up, the garment's front faces +z, metres.
#include <Eigen/Core>
#include <optional>
#include <string_view>

#include "drape/geometry/triangle_mesh.h"

namespace drape::render {

struct Camera {
  Eigen::Vector3d eye{0.0, 0.0, 3.0};
  Eigen::Vector3d target{0.0, 0.0, 0.0};
  Eigen::Vector3d up{0.0, 1.0, 0.0};
  double fovYDegrees = 30.0;
  // Clip planes in metres; nearPlane <= 0 derives both from the distance to the target.
  double nearPlane = 0.0;
  double farPlane = 0.0;

  // 4 x 4 world -> eye transform (OpenGL convention: the camera looks down -z).
  Eigen::Matrix4f viewMatrix() const;
  // 4 x 4 perspective projection for width / height = aspect.
  Eigen::Matrix4f projectionMatrix(double aspect) const;
};

// front: eye on +z looking at the garment's front; back: on -z; left: the wearer's left side (+x);
// right: the wearer's right side (-x); threeQuarter: front-left, 35 degrees around y and slightly above.
enum class ViewPreset { Front, Back, Left, Right, ThreeQuarter };

inline constexpr ViewPreset kAllViewPresets[] = {ViewPreset::Front, ViewPreset::ThreeQuarter, ViewPreset::Left,
                                                 ViewPreset::Back, ViewPreset::Right};

std::string_view viewPresetName(ViewPreset preset);  // "front", "back", "left", "right", "three-quarter"
// Parses the names above; nullopt for anything else.
std::optional<ViewPreset> parseViewPreset(std::string_view name);

// A camera looking at the centre of bounds from the preset's direction, at the smallest distance at which
// all eight corners of bounds fit in the image (aspect = width / height) with a small margin.
// Deterministic: depends only on its arguments. Empty bounds frame a unit cube at the origin.
Camera presetCamera(ViewPreset preset, const BoundingBox& bounds, double aspect, double fovYDegrees = 30.0);

// Same framing along an arbitrary viewing direction (from the target towards the eye).
Camera framingCamera(const Eigen::Vector3d& direction, const BoundingBox& bounds, double aspect,
                     double fovYDegrees = 30.0);

}  // namespace drape::render
