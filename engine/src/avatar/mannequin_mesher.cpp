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
#include <cmath>

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
  return mesh;
}

}  // namespace drape
