// Picking geometry of the viewport (no GL needed): the ray under a pixel agrees with the renderer's own
// projection (Camera::viewMatrix / projectionMatrix), ray/triangle hits and the drag plane.
#include "drape/qt/viewport_picking.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

namespace drape::test {
namespace {

// Widget pixel of a world point through the renderer's 4x4 matrices (an independent path from projectToPixel).
Eigen::Vector2d pixelByMatrices(const render::Camera& camera, const Eigen::Vector3d& p, int width, int height) {
  const Eigen::Matrix4d pv = camera.projectionMatrix(double(width) / height).cast<double>() *
                             camera.viewMatrix().cast<double>();
  const Eigen::Vector4d clip = pv * Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
  const Eigen::Vector2d ndc = clip.head<2>() / clip.w();
  return {0.5 * (ndc.x() + 1.0) * width, 0.5 * (1.0 - ndc.y()) * height};
}

double distanceToRay(const qt::Ray& ray, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - ray.origin;
  return (d - d.dot(ray.direction) * ray.direction).norm();
}

TEST(ViewportPicking, RayAndProjectionAgreeWithTheRenderersMatrices) {
  render::Camera camera;
  camera.eye = {0.7, 1.6, 2.4};
  camera.target = {0.1, 0.9, -0.2};
  camera.fovYDegrees = 35.0;
  const int width = 640, height = 400;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d p = camera.target + Eigen::Vector3d(u(rng), u(rng), u(rng));
    const Eigen::Vector2d expected = pixelByMatrices(camera, p, width, height);
    const auto projected = qt::projectToPixel(camera, p, width, height);
    ASSERT_TRUE(projected);
    EXPECT_NEAR(projected->x(), expected.x(), 1e-3);  // the matrices are float
    EXPECT_NEAR(projected->y(), expected.y(), 1e-3);
    const qt::Ray ray = qt::rayThroughPixel(camera, projected->x(), projected->y(), width, height);
    EXPECT_NEAR(ray.direction.norm(), 1.0, 1e-12);
    EXPECT_TRUE(ray.origin.isApprox(camera.eye));
    EXPECT_LT(distanceToRay(ray, p), 1e-9);
  }
  // The image centre looks at the target; a point behind the eye has no pixel.
  const qt::Ray centre = qt::rayThroughPixel(camera, width / 2.0, height / 2.0, width, height);
  EXPECT_LT(distanceToRay(centre, camera.target), 1e-12);
  EXPECT_FALSE(qt::projectToPixel(camera, camera.eye - (camera.target - camera.eye), width, height));
}

TEST(ViewportPicking, NearestTriangleAndItsNearestCorner) {
  // Two unit squares facing +z: the front one at z = 0, the back one at z = -1 (vertices 4..7).
  Eigen::MatrixX3d positions(8, 3);
  positions << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,  //
      0, 0, -1, 1, 0, -1, 1, 1, -1, 0, 1, -1;
  Eigen::MatrixX3i triangles(4, 3);
  triangles << 4, 5, 6, 4, 6, 7, 0, 1, 2, 0, 2, 3;  // back square listed first: order must not matter
  qt::Ray ray;
  ray.origin = {0.8, 0.3, 5.0};
  ray.direction = {0.0, 0.0, -1.0};
  auto hit = qt::pickTriangle(ray, positions, triangles);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->triangle, 2);  // (0.8, 0.3) lies in triangle 0-1-2 of the front square
  EXPECT_EQ(hit->vertex, 1);    // corner (1, 0, 0) is the nearest to (0.8, 0.3)
  EXPECT_NEAR(hit->distance, 5.0, 1e-12);
  EXPECT_TRUE(hit->point.isApprox(Eigen::Vector3d(0.8, 0.3, 0.0)));

  // From behind, the back square is hit first (both faces count).
  ray.origin = {0.2, 0.9, -4.0};
  ray.direction = {0.0, 0.0, 1.0};
  hit = qt::pickTriangle(ray, positions, triangles);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->vertex, 7);
  EXPECT_NEAR(hit->distance, 3.0, 1e-12);

  // An oblique ray: the hit point is where the line meets z = 0.
  ray.origin = {0.0, 0.0, 2.0};
  ray.direction = Eigen::Vector3d(0.3, 0.6, -2.0).normalized();
  hit = qt::pickTriangle(ray, positions, triangles);
  ASSERT_TRUE(hit);
  EXPECT_TRUE(hit->point.isApprox(Eigen::Vector3d(0.3, 0.6, 0.0), 1e-12));
  EXPECT_EQ(hit->vertex, 3);  // (0.3, 0.6) is nearest to (0, 1) among 0-2-3 corners

  // Misses: beside the squares, pointing away, or no triangles.
  ray.origin = {1.5, 0.5, 5.0};
  ray.direction = {0.0, 0.0, -1.0};
  EXPECT_FALSE(qt::pickTriangle(ray, positions, triangles));
  ray.origin = {0.5, 0.5, 5.0};
  ray.direction = {0.0, 0.0, 1.0};
  EXPECT_FALSE(qt::pickTriangle(ray, positions, triangles));
  EXPECT_FALSE(qt::pickTriangle(ray, positions, Eigen::MatrixX3i(0, 3)));
}

TEST(ViewportPicking, DragPlaneFacesTheCamera) {
  render::Camera camera;
  camera.eye = {0.0, 1.0, 3.0};
  camera.target = {0.0, 1.0, 0.0};
  const Eigen::Vector3d grabbed(0.2, 1.1, 0.5);
  const Eigen::Vector3d normal = qt::viewDirection(camera);
  EXPECT_TRUE(normal.isApprox(Eigen::Vector3d(0, 0, -1)));
  const int width = 300, height = 200;
  const auto pixel = qt::projectToPixel(camera, grabbed + Eigen::Vector3d(0.1, 0.2, 0.0), width, height);
  ASSERT_TRUE(pixel);
  const qt::Ray ray = qt::rayThroughPixel(camera, pixel->x(), pixel->y(), width, height);
  const auto onPlane = qt::intersectPlane(ray, grabbed, normal);
  ASSERT_TRUE(onPlane);
  EXPECT_TRUE(onPlane->isApprox(grabbed + Eigen::Vector3d(0.1, 0.2, 0.0), 1e-12));
  qt::Ray parallel;
  parallel.direction = {1.0, 0.0, 0.0};
  EXPECT_FALSE(qt::intersectPlane(parallel, grabbed, normal));
}

}  // namespace
}  // namespace drape::test
