#include "drape/qt/viewport_picking.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace drape::qt {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Camera frame as Camera::viewMatrix builds it: side s, up u, forward f (all unit).
struct Frame {
  Eigen::Vector3d s, u, f;
};

Frame frameOf(const render::Camera& camera) {
  Frame frame;
  frame.f = viewDirection(camera);
  frame.s = frame.f.cross(camera.up);
  if (frame.s.norm() < 1e-12) frame.s = frame.f.cross(Eigen::Vector3d::UnitZ());
  frame.s.normalize();
  frame.u = frame.s.cross(frame.f);
  return frame;
}

}  // namespace

Eigen::Vector3d viewDirection(const render::Camera& camera) {
  const Eigen::Vector3d d = camera.target - camera.eye;
  return d.norm() > 0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d(-Eigen::Vector3d::UnitZ());
}

Ray rayThroughPixel(const render::Camera& camera, double x, double y, int width, int height) {
  const Frame frame = frameOf(camera);
  const double w = std::max(width, 1), h = std::max(height, 1);
  const double tanHalf = std::tan(0.5 * camera.fovYDegrees * kPi / 180.0);
  const double ndcX = 2.0 * x / w - 1.0;
  const double ndcY = 1.0 - 2.0 * y / h;
  Ray ray;
  ray.origin = camera.eye;
  ray.direction = (frame.f + ndcX * tanHalf * (w / h) * frame.s + ndcY * tanHalf * frame.u).normalized();
  return ray;
}

std::optional<Eigen::Vector2d> projectToPixel(const render::Camera& camera, const Eigen::Vector3d& point, int width,
                                              int height) {
  const Frame frame = frameOf(camera);
  const Eigen::Vector3d d = point - camera.eye;
  const double depth = d.dot(frame.f);
  if (depth <= 1e-12) return std::nullopt;
  const double w = std::max(width, 1), h = std::max(height, 1);
  const double tanHalf = std::tan(0.5 * camera.fovYDegrees * kPi / 180.0);
  const double ndcX = d.dot(frame.s) / (depth * tanHalf * (w / h));
  const double ndcY = d.dot(frame.u) / (depth * tanHalf);
  return Eigen::Vector2d(0.5 * (ndcX + 1.0) * w, 0.5 * (1.0 - ndcY) * h);
}

std::optional<PickHit> pickTriangle(const Ray& ray, const Eigen::MatrixX3d& positions,
                                    const Eigen::MatrixX3i& triangles) {
  // Moller-Trumbore ray/triangle test on every triangle (a few thousand per click; no BVH needed).
  std::optional<PickHit> best;
  double bestT = std::numeric_limits<double>::infinity();
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const int i0 = triangles(t, 0), i1 = triangles(t, 1), i2 = triangles(t, 2);
    if (std::max({i0, i1, i2}) >= positions.rows() || std::min({i0, i1, i2}) < 0) continue;
    const Eigen::Vector3d a = positions.row(i0), b = positions.row(i1), c = positions.row(i2);
    const Eigen::Vector3d e1 = b - a, e2 = c - a;
    const Eigen::Vector3d p = ray.direction.cross(e2);
    const double det = e1.dot(p);
    const double scale = e1.norm() * e2.norm();
    if (std::abs(det) <= 1e-14 * std::max(scale, 1e-300)) continue;  // parallel or degenerate
    const double inv = 1.0 / det;
    const Eigen::Vector3d s = ray.origin - a;
    const double u = s.dot(p) * inv;
    if (u < 0.0 || u > 1.0) continue;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = ray.direction.dot(q) * inv;
    if (v < 0.0 || u + v > 1.0) continue;
    const double distance = e2.dot(q) * inv;
    if (distance <= 0.0 || distance >= bestT) continue;
    bestT = distance;
    PickHit hit;
    hit.triangle = static_cast<int>(t);
    hit.distance = distance;
    hit.point = ray.origin + distance * ray.direction;
    const int corners[3] = {i0, i1, i2};
    double nearest = std::numeric_limits<double>::infinity();
    for (int corner : corners) {
      const double d = (positions.row(corner).transpose() - hit.point).squaredNorm();
      if (d < nearest) {
        nearest = d;
        hit.vertex = corner;
      }
    }
    best = hit;
  }
  return best;
}

std::optional<Eigen::Vector3d> intersectPlane(const Ray& ray, const Eigen::Vector3d& planePoint,
                                              const Eigen::Vector3d& planeNormal) {
  const double denom = ray.direction.dot(planeNormal);
  if (std::abs(denom) < 1e-12) return std::nullopt;
  const double t = (planePoint - ray.origin).dot(planeNormal) / denom;
  if (t <= 0.0) return std::nullopt;
  return Eigen::Vector3d(ray.origin + t * ray.direction);
}

}  // namespace drape::qt
