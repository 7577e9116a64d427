#include "synthetic_scenes.h"

#include <Eigen/Geometry>
#include <cmath>
#include <functional>

#include "drape/geometry/primitives.h"
#include "drape/geometry/strain.h"

namespace drape::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Orients every triangle so its normal points along outward(centroid) (front faces outside).
void orientTriangles(const Eigen::MatrixX3d& positions, Eigen::MatrixX3i& triangles,
                     const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& outward) {
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const Eigen::Vector3d a = positions.row(triangles(f, 0)), b = positions.row(triangles(f, 1)),
                          c = positions.row(triangles(f, 2));
    if ((b - a).cross(c - a).dot(outward((a + b + c) / 3.0)) < 0.0) std::swap(triangles(f, 1), triangles(f, 2));
  }
}

}  // namespace

Snapshot tableclothScene(int cells, double side, int sphereSubdivisions) {
  const Eigen::Vector3d center(0.0, 0.45, 0.0);
  const double radius = 0.25, lift = 0.006, capAngle = 55.0 * kPi / 180.0;
  const int n = cells + 1;
  Snapshot s;
  s.positions.resize(n * n, 3);
  s.uvs.resize(n * n, 2);
  s.vertexContact = Eigen::VectorXi::Zero(n * n);
  const double capLength = radius * capAngle;  // geodesic radius of the cap lying on the sphere
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v = j * n + i;
      const double u = side * (double(i) / cells - 0.5), w = side * (double(j) / cells - 0.5);
      s.uvs.row(v) << u, w;
      const double r = std::hypot(u, w), theta = std::atan2(w, u);
      double rho, y;
      if (r <= capLength) {
        const double phi = r / radius;
        rho = (radius + lift) * std::sin(phi);
        y = center.y() + (radius + lift) * std::cos(phi);
        s.vertexContact(v) = 1;
      } else {
        // Integrate the hanging curve: the slope turns from the cap's tangent towards vertical.
        rho = (radius + lift) * std::sin(capAngle);
        y = center.y() + (radius + lift) * std::cos(capAngle);
        const double length = r - capLength;
        const int steps = 40;
        const double ds = length / steps;
        for (int k = 0; k < steps; ++k) {
          const double t = (k + 0.5) * ds;
          const double psi = capAngle + (0.5 * kPi - capAngle) * (1.0 - std::exp(-t / 0.15));
          rho += std::cos(psi) * ds;
          y -= std::sin(psi) * ds;
        }
        const double fold = std::min(length / 0.25, 1.0);
        // Folds only push outwards, so the cloth never enters the sphere.
        rho *= 1.0 + 0.05 * fold * (0.5 + 0.5 * std::cos(2.0 * theta));
        rho += 0.04 * fold * fold * (0.5 + 0.5 * std::sin(7.0 * theta));
      }
      s.positions.row(v) << center.x() + rho * std::cos(theta), y, center.z() + rho * std::sin(theta);
    }
  s.triangles.resize(2 * cells * cells, 3);
  s.trianglePanel.resize(2 * cells * cells);
  s.triangleDomain.resize(2 * cells * cells);
  int f = 0;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      const int panel = i < cells / 2 ? 0 : 1;
      const int domain = (i < cells / 2 ? 0 : 1) + (j < cells / 2 ? 0 : 2);
      s.triangles.row(f) << a, c, b;
      s.trianglePanel(f) = panel, s.triangleDomain(f) = domain, ++f;
      s.triangles.row(f) << b, c, d;
      s.trianglePanel(f) = panel, s.triangleDomain(f) = domain, ++f;
    }
  orientTriangles(s.positions, s.triangles, [&](const Eigen::Vector3d& p) { return Eigen::Vector3d(p - center); });
  s.panelColors = {Eigen::Vector3f(0.55f, 0.12f, 0.10f), Eigen::Vector3f(0.10f, 0.24f, 0.50f)};
  s.triangleStrain = triangleStretch(s.uvs, s.positions, s.triangles);
  s.avatar = makeIcosphere(center, radius, sphereSubdivisions);
  s.stage = Stage::Placed;
  return s;
}

Snapshot skirtScene(int rings, int segments, int sphereSubdivisions) {
  const Eigen::Vector3d center(0.0, 0.95, 0.0);
  const double sphereRadius = 0.22, top = 0.95, bottom = 0.30, restRadius = 0.27;
  Snapshot s;
  const int columns = segments + 1;  // the seam column is duplicated so the rest pattern stays flat
  s.positions.resize((rings + 1) * columns, 3);
  s.uvs.resize((rings + 1) * columns, 2);
  s.vertexContact = Eigen::VectorXi::Zero((rings + 1) * columns);
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < columns; ++i) {
      const int v = j * columns + i;
      const double t = double(j) / rings;  // 0 at the waist, 1 at the hem
      const double theta = 2.0 * kPi * i / segments;
      const double radius = (sphereRadius + 0.004) * (1.0 - t) + 0.31 * t + 0.035 * t * t * std::sin(9.0 * theta);
      const double y = top + (bottom - top) * t;
      s.positions.row(v) << radius * std::sin(theta), y, radius * std::cos(theta);
      s.uvs.row(v) << restRadius * theta, y;
      if (j == 0) s.vertexContact(v) = 1;
    }
  s.triangles.resize(2 * rings * segments, 3);
  s.trianglePanel.resize(2 * rings * segments);
  s.triangleDomain.resize(2 * rings * segments);
  int f = 0;
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      const int a = j * columns + i, b = a + 1, c = a + columns, d = c + 1;
      const double theta = 2.0 * kPi * (i + 0.5) / segments;
      const int panel = std::cos(theta) >= 0.0 ? 0 : 1;  // front faces +z
      const int domain = static_cast<int>(6.0 * i / segments);
      s.triangles.row(f) << a, b, c;
      s.trianglePanel(f) = panel, s.triangleDomain(f) = domain, ++f;
      s.triangles.row(f) << b, d, c;
      s.trianglePanel(f) = panel, s.triangleDomain(f) = domain, ++f;
    }
  orientTriangles(s.positions, s.triangles,
                  [](const Eigen::Vector3d& p) { return Eigen::Vector3d(p.x(), 0.0, p.z()); });
  s.panelColors = {Eigen::Vector3f(0.62f, 0.30f, 0.12f), Eigen::Vector3f(0.16f, 0.36f, 0.30f)};
  s.triangleStrain = triangleStretch(s.uvs, s.positions, s.triangles);
  s.avatar = makeIcosphere(center, sphereRadius, sphereSubdivisions);
  s.stage = Stage::Preview;
  return s;
}

}  // namespace drape::test
