// makeMannequin: the implicit body of mannequin_shape.h meshed with CGAL's surface mesher (Boissonnat and
// Oudot's Delaunay refinement, CGAL::make_surface_mesh). The only file that includes CGAL's mesher.
#include <CGAL/Complex_2_in_triangulation_3.h>
#include <CGAL/IO/facets_in_complex_2_to_triangle_mesh.h>
#include <CGAL/Implicit_surface_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_default_triangulation_3.h>
#include <CGAL/make_surface_mesh.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <vector>

#include "avatar/mannequin_shape.h"
#include "drape/avatar/mannequin.h"

namespace drape {
namespace {

using Triangulation = CGAL::Surface_mesh_default_triangulation_3;
using Complex = CGAL::Complex_2_in_triangulation_3<Triangulation>;
using Kernel = Triangulation::Geom_traits;
using Point = Kernel::Point_3;
using OutputMesh = CGAL::Surface_mesh<Point>;

// The implicit function as CGAL wants it: a callable on points.
struct ShapeFunction {
  const mannequin_detail::MannequinShape* shape;
  Kernel::FT operator()(const Point& p) const { return shape->value(Eigen::Vector3d(p.x(), p.y(), p.z())); }
};

double signedVolume(const TriangleMesh& mesh) {
  double volume = 0.0;
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.triangles(f, 0));
    const Eigen::Vector3d b = mesh.vertices.row(mesh.triangles(f, 1));
    const Eigen::Vector3d c = mesh.vertices.row(mesh.triangles(f, 2));
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

// The mesh in a canonical order: vertices sorted by position (x, then y, then z), each triangle starting at its
// smallest index (orientation kept), triangles sorted. CGAL's complex hands its facets over in an order that follows
// memory addresses, which differ from run to run; the vertices and triangles themselves do not.
void canonicalOrder(TriangleMesh& mesh) {
  const int n = static_cast<int>(mesh.vertices.rows());
  std::vector<int> order(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) order[static_cast<size_t>(i)] = i;
  auto position = [&](int i) {
    return std::make_tuple(mesh.vertices(i, 0), mesh.vertices(i, 1), mesh.vertices(i, 2));
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return position(a) < position(b); });
  std::vector<int> newIndex(static_cast<size_t>(n));
  Eigen::MatrixX3d vertices(n, 3);
  for (int k = 0; k < n; ++k) {
    newIndex[static_cast<size_t>(order[static_cast<size_t>(k)])] = k;
    vertices.row(k) = mesh.vertices.row(order[static_cast<size_t>(k)]);
  }
  std::vector<std::array<int, 3>> triangles(static_cast<size_t>(mesh.triangles.rows()));
  for (size_t f = 0; f < triangles.size(); ++f) {
    std::array<int, 3> t;
    for (int c = 0; c < 3; ++c) t[static_cast<size_t>(c)] = newIndex[static_cast<size_t>(mesh.triangles(static_cast<int>(f), c))];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    triangles[f] = t;
  }
  std::sort(triangles.begin(), triangles.end());
  mesh.vertices = std::move(vertices);
  for (size_t f = 0; f < triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) mesh.triangles(static_cast<int>(f), c) = triangles[f][static_cast<size_t>(c)];
}

}  // namespace

MannequinLevels mannequinLevels(const BodyMeasurements& measurements) {
  return mannequin_detail::levelsFor(measurements);
}

TriangleMesh makeMannequin(const BodyMeasurements& measurements, const MannequinOptions& options) {
  const mannequin_detail::MannequinShape shape(measurements);

  // A bounding sphere centred on a point inside the body that holds the whole box.
  const Eigen::Vector3d centre = shape.interiorPoint();
  const BoundingBox& box = shape.bounds();
  double radius = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d q((corner & 1) ? box.max.x() : box.min.x(), (corner & 2) ? box.max.y() : box.min.y(),
                            (corner & 4) ? box.max.z() : box.min.z());
    radius = std::max(radius, (q - centre).norm());
  }
  radius += 0.05;

  Triangulation triangulation;
  Complex complex(triangulation);
  const ShapeFunction function{&shape};
  // The error bound is relative to the sphere's radius: the precision of the surface-segment intersections.
  CGAL::Implicit_surface_3<Kernel, ShapeFunction> surface(
      function, Kernel::Sphere_3(Point(centre.x(), centre.y(), centre.z()), radius * radius), 1e-6);
  CGAL::Surface_mesh_default_criteria_3<Triangulation> criteria(options.facetAngle, options.facetSize,
                                                                options.facetDistance);
  // The initial surface points come from CGAL's (thread-local) default random generator: reseed it so that the
  // same measurements always give the same mesh.
  CGAL::get_default_random() = CGAL::Random(0);
  CGAL::make_surface_mesh(complex, surface, criteria, CGAL::Manifold_tag(), 100);

  OutputMesh output;
  CGAL::facets_in_complex_2_to_triangle_mesh(complex, output);

  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(output.number_of_vertices()), 3);
  std::vector<int> index(output.num_vertices(), -1);
  int next = 0;
  for (auto v : output.vertices()) {
    const Point& p = output.point(v);
    index[v.idx()] = next;
    mesh.vertices.row(next++) << p.x(), p.y(), p.z();
  }
  mesh.vertices.conservativeResize(next, 3);
  mesh.triangles.resize(static_cast<Eigen::Index>(output.number_of_faces()), 3);
  int face = 0;
  for (auto f : output.faces()) {
    int corner = 0;
    for (auto v : CGAL::vertices_around_face(output.halfedge(f), output))
      mesh.triangles(face, corner++) = index[v.idx()];
    ++face;
  }
  mesh.triangles.conservativeResize(face, 3);

  // Outward orientation, and the soles exactly on the floor.
  if (signedVolume(mesh) < 0.0) mesh.triangles.col(1).swap(mesh.triangles.col(2));
  mesh.vertices.col(1).array() -= mesh.vertices.col(1).minCoeff();
  canonicalOrder(mesh);
  return mesh;
}

}  // namespace drape
