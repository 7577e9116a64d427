// The exact triangle-triangle test of self_intersection.h. It is the one collision file that includes CGAL, so it
// is compiled in the drape_engine_cgal object library with CGAL's flags (engine/CMakeLists.txt).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include "drape/collision/self_intersection.h"

namespace drape::collision {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Triangle = Kernel::Triangle_3;

Point point(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), p.z()};
}

// A triangle, or what is left of a collapsed one: the segment between its two farthest corners, or a point.
struct Simplex {
  int dimension = 2;
  Triangle triangle;
  Segment segment;
  Point single;
};

Simplex simplexOf(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  Simplex s;
  const Point p = point(a), q = point(b), r = point(c);
  if (!CGAL::collinear(p, q, r)) {
    s.triangle = Triangle(p, q, r);
    return s;
  }
  // Collinear: the two corners farthest apart span the others.
  const double ab = (a - b).squaredNorm(), bc = (b - c).squaredNorm(), ca = (c - a).squaredNorm();
  Point u = p, v = q;
  if (bc >= ab && bc >= ca) {
    u = q;
    v = r;
  } else if (ca >= ab && ca >= bc) {
    u = r;
    v = p;
  }
  if (u == v) {
    s.dimension = 0;
    s.single = u;
  } else {
    s.dimension = 1;
    s.segment = Segment(u, v);
  }
  return s;
}

bool intersect(const Simplex& a, const Simplex& b) {
  if (a.dimension < b.dimension) return intersect(b, a);
  if (a.dimension == 2) {
    if (b.dimension == 2) return CGAL::do_intersect(a.triangle, b.triangle);
    if (b.dimension == 1) return CGAL::do_intersect(a.triangle, b.segment);
    return a.triangle.has_on(b.single);
  }
  if (a.dimension == 1) {
    if (b.dimension == 1) return CGAL::do_intersect(a.segment, b.segment);
    return a.segment.has_on(b.single);
  }
  return a.single == b.single;
}

}  // namespace

bool trianglesIntersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                        const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2) {
  return intersect(simplexOf(a0, a1, a2), simplexOf(b0, b1, b2));
}

}  // namespace drape::collision
