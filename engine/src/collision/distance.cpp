// Closest-point queries by Voronoi-region classification (Ericson, Real-Time Collision Detection, 5.1).
#include "drape/collision/distance.h"

#include <Eigen/Geometry>

#include <algorithm>

namespace drape::collision {
namespace {

double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }

PointTriangleResult makeResult(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c, double wb, double wc, TriangleRegion region) {
  PointTriangleResult r;
  r.barycentric = Eigen::Vector3d(std::max(0.0, 1.0 - wb - wc), wb, wc);  // wb + wc may round past 1 on edge BC
  r.closest = r.barycentric[0] * a + wb * b + wc * c;
  r.region = region;
  r.distanceSquared = (p - r.closest).squaredNorm();
  return r;
}

// Degenerate triangle: the best of its three edges (vertices come out as edge endpoints).
PointTriangleResult closestOnEdges(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c) {
  const PointSegmentResult ab = closestPointSegment(p, a, b);
  const PointSegmentResult bc = closestPointSegment(p, b, c);
  const PointSegmentResult ca = closestPointSegment(p, c, a);
  auto region = [](double t, TriangleRegion start, TriangleRegion edge, TriangleRegion end) {
    return t <= 0.0 ? start : (t >= 1.0 ? end : edge);
  };
  if (ab.distanceSquared <= bc.distanceSquared && ab.distanceSquared <= ca.distanceSquared) {
    return makeResult(p, a, b, c, ab.t, 0.0,
                      region(ab.t, TriangleRegion::VertexA, TriangleRegion::EdgeAB, TriangleRegion::VertexB));
  }
  if (bc.distanceSquared <= ca.distanceSquared) {
    return makeResult(p, a, b, c, 1.0 - bc.t, bc.t,
                      region(bc.t, TriangleRegion::VertexB, TriangleRegion::EdgeBC, TriangleRegion::VertexC));
  }
  return makeResult(p, a, b, c, 0.0, 1.0 - ca.t,
                    region(ca.t, TriangleRegion::VertexC, TriangleRegion::EdgeCA, TriangleRegion::VertexA));
}

}  // namespace

PointSegmentResult closestPointSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  PointSegmentResult r;
  r.t = len2 > 0.0 ? clamp01((p - a).dot(ab) / len2) : 0.0;
  r.distanceSquared = (p - (a + r.t * ab)).squaredNorm();
  return r;
}

PointTriangleResult closestPointTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  const double area2 = ab.cross(ac).squaredNorm();
  if (!(area2 > 1e-24 * ab.squaredNorm() * ac.squaredNorm()) || area2 == 0.0) return closestOnEdges(p, a, b, c);

  const Eigen::Vector3d ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return makeResult(p, a, b, c, 0.0, 0.0, TriangleRegion::VertexA);

  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return makeResult(p, a, b, c, 1.0, 0.0, TriangleRegion::VertexB);

  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    return makeResult(p, a, b, c, d1 / (d1 - d3), 0.0, TriangleRegion::EdgeAB);
  }

  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return makeResult(p, a, b, c, 0.0, 1.0, TriangleRegion::VertexC);

  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    return makeResult(p, a, b, c, 0.0, d2 / (d2 - d6), TriangleRegion::EdgeCA);
  }

  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return makeResult(p, a, b, c, 1.0 - w, w, TriangleRegion::EdgeBC);
  }

  const double inv = 1.0 / (va + vb + vc);
  return makeResult(p, a, b, c, vb * inv, vc * inv, TriangleRegion::Face);
}

EdgeEdgeResult closestPointsEdgeEdge(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                                     const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0;
  const Eigen::Vector3d d2 = q1 - q0;
  const Eigen::Vector3d r = p0 - q0;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double f = d2.dot(r);
  EdgeEdgeResult out;
  if (a <= 0.0 && e <= 0.0) {
    out.parallel = true;
  } else if (a <= 0.0) {
    out.t = clamp01(f / e);
    out.parallel = true;
  } else {
    const double c = d1.dot(r);
    if (e <= 0.0) {
      out.s = clamp01(-c / a);
      out.parallel = true;
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;  // |d1 x d2|^2, >= 0
      if (denom > 1e-12 * a * e) {
        out.s = clamp01((b * f - c * e) / denom);
      } else {
        out.s = 0.0;
        out.parallel = true;
      }
      out.t = (b * out.s + f) / e;
      if (out.t < 0.0) {
        out.t = 0.0;
        out.s = clamp01(-c / a);
      } else if (out.t > 1.0) {
        out.t = 1.0;
        out.s = clamp01((b - c) / a);
      }
    }
  }
  out.distanceSquared = ((p0 + out.s * d1) - (q0 + out.t * d2)).squaredNorm();
  return out;
}

}  // namespace drape::collision
