// Panel meshing with CGAL's 2D constrained Delaunay mesher. All CGAL includes
// of the engine live in this one file (CGAL compiles slowly). The mesher used
// never splits constrained edges (Delaunay_mesher_no_edge_refinement_2): a
// refinement point that would encroach a boundary edge is skipped, so the
// boundary points given are exactly the boundary vertices of the mesh.
#include "drape/garment/panel_mesher.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_no_edge_refinement_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

#include "drape/core/input_error.h"
#include "drape/geometry/spatial_order.h"

namespace drape {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;
using Segment = Kernel::Segment_2;

// Index of the vertex in the output; -1 for points the mesher inserted
// (numbered after extraction).
struct VertexIndex {
  int value = -1;
};

using VertexBase =
    CGAL::Delaunay_mesh_vertex_base_2<Kernel, CGAL::Triangulation_vertex_base_with_info_2<VertexIndex, Kernel>>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::No_constraint_intersection_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Mesher = CGAL::Delaunay_mesher_no_edge_refinement_2<Cdt, Criteria>;

// Refuse meshes estimated above this many triangles rather than run for minutes
// and exhaust memory.
constexpr double kMaxTriangles = 5.0e6;
// Refinement criteria: largest edge at most kSizeFactor * target; smallest
// angle at least ~25.7 degrees (CGAL's bound is on the squared sine of the
// smallest angle: sin^2(25.7 deg) = 0.188).
constexpr double kSizeFactor = 1.3;
constexpr double kAspectBound = 0.188;

[[noreturn]] void fail(const std::string& context, const std::string& what) {
  throw InputError(context.empty() ? what : context + ": " + what);
}

double signedArea(const std::vector<Eigen::Vector2d>& b) {
  double twice = 0.0;
  for (size_t i = 0, n = b.size(); i < n; ++i) {
    const Eigen::Vector2d& p = b[i];
    const Eigen::Vector2d& q = b[(i + 1) % n];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice;
}

// Names the first pair of boundary segments that intersect (other than
// neighbours at their shared point). Exact predicates; segments are pruned by
// their x extent.
std::string findSelfIntersection(const std::vector<Point>& pts) {
  const size_t n = pts.size();
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  auto minX = [&](size_t i) { return std::min(pts[i].x(), pts[(i + 1) % n].x()); };
  auto maxX = [&](size_t i) { return std::max(pts[i].x(), pts[(i + 1) % n].x()); };
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return minX(a) < minX(b); });
  for (size_t k = 0; k < n; ++k) {
    const size_t i = order[k];
    const Segment si(pts[i], pts[(i + 1) % n]);
    for (size_t m = k + 1; m < n && minX(order[m]) <= maxX(i); ++m) {
      const size_t j = order[m];
      const Segment sj(pts[j], pts[(j + 1) % n]);
      const bool adjacent = (j == (i + 1) % n) || (i == (j + 1) % n);
      bool bad = false;
      if (!adjacent) {
        bad = CGAL::do_intersect(si, sj);
      } else {
        // Neighbours share one endpoint; they are bad only if they overlap (the
        // outline doubles back).
        const size_t shared = (j == (i + 1) % n) ? j : i;
        const size_t a = (shared == j) ? i : j;  // segment before the shared point starts at a
        const size_t c = (shared + 1) % n;       // segment after it ends at c
        const Point& pa = pts[a];
        const Point& ps = pts[shared];
        const Point& pc = pts[c];
        bad = CGAL::collinear(pa, ps, pc) && !CGAL::collinear_are_strictly_ordered_along_line(pa, ps, pc);
      }
      if (bad) {
        std::ostringstream msg;
        msg << "boundary is self-intersecting (segment " << std::min(i, j) << " from point " << std::min(i, j)
            << " meets segment " << std::max(i, j) << ")";
        return msg.str();
      }
    }
  }
  return "boundary is self-intersecting";
}

void validate(const std::vector<Eigen::Vector2d>& boundary, double target, const std::string& context) {
  if (boundary.size() < 3) {
    fail(context, "boundary has " + std::to_string(boundary.size()) + " points, at least 3 are needed");
  }
  if (!std::isfinite(target) || target <= 0.0) {
    std::ostringstream msg;
    msg << "target edge length must be positive and finite (got " << target << ")";
    fail(context, msg.str());
  }
  Eigen::Vector2d lo = boundary[0], hi = boundary[0];
  for (size_t i = 0; i < boundary.size(); ++i) {
    if (!boundary[i].allFinite()) fail(context, "boundary point " + std::to_string(i) + " is not finite");
    lo = lo.cwiseMin(boundary[i]);
    hi = hi.cwiseMax(boundary[i]);
  }
  std::vector<Point> pts;
  pts.reserve(boundary.size());
  for (const auto& p : boundary) pts.emplace_back(p.x(), p.y());
  const std::string zeroArea = "boundary encloses zero area (" + std::to_string(boundary.size()) + " points)";
  const bool allCollinear = std::all_of(pts.begin() + 2, pts.end(), [&](const Point& p) {
    return pts[0] == pts[1] || CGAL::collinear(pts[0], pts[1], p);
  });
  if (allCollinear) fail(context, zeroArea);
  if (!CGAL::is_simple_2(pts.begin(), pts.end(), Kernel())) fail(context, findSelfIntersection(pts));
  const double diag = (hi - lo).norm();
  const double area = std::abs(signedArea(boundary));
  if (!(area > 1e-14 * diag * diag)) fail(context, zeroArea);

  const double estimate = area / (std::sqrt(3.0) / 4.0 * target * target);
  if (estimate > kMaxTriangles) {
    std::ostringstream msg;
    msg << "target edge length " << target << " would give about " << static_cast<long long>(estimate)
        << " triangles, more than the limit of " << static_cast<long long>(kMaxTriangles)
        << "; choose a larger target edge length";
    fail(context, msg.str());
  }
}

// Marks the faces inside the outline as the domain: a face is inside when
// reaching it from the infinite face crosses an odd number of constrained
// edges.
void markDomain(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->set_in_domain(false);
  std::vector<std::pair<Cdt::Face_handle, int>> stack;  // face, nesting level
  std::map<Cdt::Face_handle, int> level;                // faces already reached
  stack.emplace_back(cdt.infinite_face(), 0);
  level[cdt.infinite_face()] = 0;
  while (!stack.empty()) {
    auto [f, lv] = stack.back();
    stack.pop_back();
    f->set_in_domain(lv % 2 == 1);
    for (int i = 0; i < 3; ++i) {
      Cdt::Face_handle g = f->neighbor(i);
      if (level.count(g)) continue;
      const int glv = lv + (f->is_constrained(i) ? 1 : 0);
      level[g] = glv;
      stack.emplace_back(g, glv);
    }
  }
}

// CGAL numbers the inserted points in its own (scattered) order. Renumbers them along a Hilbert curve after the
// boundary points, and sorts the triangles along the same curve by centroid, so that triangles and vertices
// close in the plane are close in memory (the solvers' assembly and sparse products are memory bound).
void orderForLocality(int boundaryCount, PanelMesh& mesh) {
  const int total = static_cast<int>(mesh.vertices.rows());
  const std::vector<int> interior = hilbertOrder(mesh.vertices.bottomRows(total - boundaryCount));
  std::vector<int> newIndex(total);
  std::iota(newIndex.begin(), newIndex.begin() + boundaryCount, 0);
  Eigen::MatrixX2d vertices = mesh.vertices;
  for (int k = 0; k < static_cast<int>(interior.size()); ++k) {
    newIndex[boundaryCount + interior[k]] = boundaryCount + k;
    vertices.row(boundaryCount + k) = mesh.vertices.row(boundaryCount + interior[k]);
  }
  mesh.vertices = std::move(vertices);
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t)
    for (int c = 0; c < 3; ++c) mesh.triangles(t, c) = newIndex[mesh.triangles(t, c)];
  Eigen::MatrixX2d centroids(mesh.triangles.rows(), 2);
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t)
    centroids.row(t) = (mesh.vertices.row(mesh.triangles(t, 0)) + mesh.vertices.row(mesh.triangles(t, 1)) +
                        mesh.vertices.row(mesh.triangles(t, 2))) / 3.0;
  const std::vector<int> triangleOrder = hilbertOrder(centroids);
  Eigen::MatrixX3i triangles(mesh.triangles.rows(), 3);
  for (size_t k = 0; k < triangleOrder.size(); ++k)
    triangles.row(static_cast<Eigen::Index>(k)) = mesh.triangles.row(triangleOrder[k]);
  mesh.triangles = std::move(triangles);
}

}  // namespace

PanelMesh meshPanel(const std::vector<Eigen::Vector2d>& boundary, double targetEdgeLength, const std::string& context) {
  validate(boundary, targetEdgeLength, context);
  const int n = static_cast<int>(boundary.size());

  Cdt cdt;
  std::vector<Cdt::Vertex_handle> handles(n);
  try {
    for (int i = 0; i < n; ++i) {
      handles[i] = cdt.insert(Point(boundary[i].x(), boundary[i].y()));
      handles[i]->info().value = i;
    }
    for (int i = 0; i < n; ++i) cdt.insert_constraint(handles[i], handles[(i + 1) % n]);
  } catch (const std::exception& e) {
    fail(context, std::string("boundary could not be triangulated: ") + e.what());
  }
  if (static_cast<int>(cdt.number_of_vertices()) != n) fail(context, "boundary has coincident points");

  markDomain(cdt);
  Mesher mesher(cdt, Criteria(kAspectBound, kSizeFactor * targetEdgeLength));
  mesher.init(true);
  mesher.refine_mesh();

  // Number the inserted points after the boundary, in triangulation order.
  int next = n;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    if (v->info().value < 0) v->info().value = next++;
  }
  PanelMesh mesh;
  mesh.vertices.resize(next, 2);
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    const int i = v->info().value;
    if (i < n) {
      mesh.vertices.row(i) = boundary[i].transpose();  // bit for bit the input
    } else {
      mesh.vertices(i, 0) = v->point().x();
      mesh.vertices(i, 1) = v->point().y();
    }
  }
  std::vector<Eigen::Vector3i> tris;
  tris.reserve(cdt.number_of_faces());
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    // CGAL stores faces counter-clockwise in the plane, whatever the
    // orientation of the outline.
    tris.emplace_back(f->vertex(0)->info().value, f->vertex(1)->info().value, f->vertex(2)->info().value);
  }
  mesh.triangles.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (size_t t = 0; t < tris.size(); ++t) mesh.triangles.row(static_cast<Eigen::Index>(t)) = tris[t].transpose();
  orderForLocality(n, mesh);
  return mesh;
}

}  // namespace drape
