#pragma once
// Picking in the viewport: the ray under a widget pixel, the garment vertex a ray hits, the inverse (a world
// point to its widget pixel) and the drag plane that faces the camera. Pure geometry on the same camera
// conventions as drape::render::Camera (viewMatrix / projectionMatrix), so it needs no GL context.
#include <Eigen/Core>
#include <optional>

#include "drape/render/camera.h"

namespace drape::qt {

// A ray from origin along direction (unit), metres.
struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
};

// What a ray hit on the garment.
struct PickHit {
  int triangle = -1;                                  // row of the triangles matrix
  int vertex = -1;                                    // the hit triangle's vertex nearest to point
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    // hit point, metres
  double distance = 0.0;                              // along the ray from its origin, metres
};

// The ray through widget position (x, y) (pixels, origin top left, y down) of a width x height widget seen
// through camera. Pixel coordinates may be fractional; (0, 0) is the top-left corner of the image.
Ray rayThroughPixel(const render::Camera& camera, double x, double y, int width, int height);

// The widget position (pixels, origin top left) where point appears; nullopt behind the camera.
std::optional<Eigen::Vector2d> projectToPixel(const render::Camera& camera, const Eigen::Vector3d& point, int width,
                                              int height);

// The nearest triangle of (positions |V| x 3 metres, triangles |F| x 3) the ray hits in front of its origin
// (both faces count) and, of its three corners, the vertex nearest to the hit point; nullopt when it misses.
std::optional<PickHit> pickTriangle(const Ray& ray, const Eigen::MatrixX3d& positions,
                                    const Eigen::MatrixX3i& triangles);

// Where the ray meets the plane through planePoint with normal planeNormal; nullopt when the ray is parallel
// to the plane or meets it behind its origin.
std::optional<Eigen::Vector3d> intersectPlane(const Ray& ray, const Eigen::Vector3d& planePoint,
                                              const Eigen::Vector3d& planeNormal);

// Unit viewing direction of the camera (from the eye towards the target): the normal of the drag plane.
Eigen::Vector3d viewDirection(const render::Camera& camera);

}  // namespace drape::qt
