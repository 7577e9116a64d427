#include "drape/sim/drape_quality.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "drape/collision/avatar_collider.h"
#include "drape/collision/garment_facing.h"
#include "drape/collision/self_intersection.h"
#include "drape/geometry/strain.h"
#include "drape/scene/settings.h"
#include "drape/sim/simulation.h"
#include "sim/garment_place.h"

namespace drape {
namespace {

template <class... Args>
std::string format(const char* pattern, Args... args) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, pattern, args...);
  return buffer;
}

QualityCheck strainCheck(const Garment& garment, const Eigen::MatrixX3d& x, const QualitySettings& s) {
  QualityCheck c;
  c.name = "max_strain";
  c.threshold = s.maxStrain;
  const Eigen::VectorXd stretch = triangleStretch(garment.rest, x, garment.triangles);
  if (stretch.size() > 0) {
    c.value = stretch.maxCoeff(&c.triangle);
    c.where = triangleName(garment, c.triangle) + atPoint(triangleCentre(garment, x, c.triangle));
  }
  c.passed = !(c.value > c.threshold);  // a NaN stretch fails
  c.message =
      format("max_strain: a triangle stretched %.1f %% (threshold %.1f %%), ", 100.0 * c.value, 100.0 * c.threshold) +
      (c.where.empty() ? "no triangles" : c.where);
  return c;
}

// inside_fraction, penetration_depth and near_skin_fraction from every vertex's signed distance to the collider.
void colliderChecks(const Garment& garment, const Eigen::MatrixX3d& x, const collision::AvatarCollider& collider,
                    double thickness, const QualitySettings& s, std::vector<QualityCheck>& checks) {
  const int n = static_cast<int>(x.rows());
  std::vector<double> distance(n);
  tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& range) {
    for (int v = range.begin(); v != range.end(); ++v) distance[v] = collider.signedDistance(x.row(v).transpose());
  });
  int inside = 0, near = 0, deepest = -1;
  for (int v = 0; v < n; ++v) {
    if (distance[v] < 0.0) ++inside;
    if (distance[v] < s.nearSkinDistance) ++near;
    if (deepest < 0 || distance[v] < distance[deepest]) deepest = v;
  }
  const double count = std::max(1, n);
  const std::string place = deepest < 0 ? std::string("no vertices") : vertexPlace(garment, x, deepest);

  // A check that passes while its value stays at or below its threshold, worst at `deepest`.
  const auto atMost = [&](const char* name, double value, double threshold, const std::string& message) {
    QualityCheck c;
    c.name = name;
    c.value = value;
    c.threshold = threshold;
    c.passed = !(value > threshold);
    c.vertex = deepest;
    c.where = place;
    c.message = message + place;
    checks.push_back(c);
  };
  const double fractionInside = inside / count, nearFraction = near / count;
  atMost("inside_fraction", fractionInside, s.maxInsideFraction,
         format("inside_fraction: %.2f %% of the garment vertices inside a collider (threshold %.2f %%); deepest: ",
                100.0 * fractionInside, 100.0 * s.maxInsideFraction));
  const double depth = deepest < 0 ? 0.0 : std::max(0.0, -distance[deepest]);
  const double depthThreshold = s.maxPenetrationDepth > 0.0 ? s.maxPenetrationDepth : thickness;
  atMost("penetration_depth", depth, depthThreshold,
         format("penetration_depth: a vertex %.1f mm inside a collider (threshold %.1f mm), ", 1e3 * depth,
                1e3 * depthThreshold));
  atMost("near_skin_fraction", nearFraction, s.maxNearSkinFraction,
         format("near_skin_fraction: %.2f %% of the garment vertices within %.1f mm of a collider or inside "
                "(threshold %.2f %%); deepest: ",
                100.0 * nearFraction, 1e3 * s.nearSkinDistance, 100.0 * s.maxNearSkinFraction));
}

// Faces whose centroid lies within this distance of a collider count for outward_faces, metres: the cloth on the
// body, not the upper layers of the folds over it.
constexpr double kOutwardNearDistance = 0.01;

QualityCheck outwardCheck(const Garment& garment, const Eigen::MatrixX3d& x, const collision::AvatarCollider& collider,
                          const QualitySettings& s) {
  const collision::GarmentFacing facing =
      collision::garmentFacing(x, garment.triangles, collider, kOutwardNearDistance);
  QualityCheck c;
  c.name = "outward_faces";
  c.value = facing.outwardFraction();
  c.threshold = s.minOutwardFraction;
  c.passed = c.value >= c.threshold;
  c.triangle = facing.inwardFace;
  if (facing.inwardFace >= 0)
    c.where = triangleName(garment, facing.inwardFace) + atPoint(triangleCentre(garment, x, facing.inwardFace));
  c.message =
      format("outward_faces: %.1f %% of the %d garment faces on a collider face away from it (threshold %.1f %%)",
             100.0 * c.value, facing.nearFaces, 100.0 * c.threshold) +
      (c.where.empty() ? std::string() : "; facing into it: " + c.where);
  return c;
}

QualityCheck selfIntersectionCheck(const Garment& garment, const Eigen::MatrixX3d& x, const QualitySettings& s) {
  // Both sides of a seam count as one vertex: sewn vertex to vertex, or (non-conforming) vertex to edge.
  std::vector<std::pair<int, int>> joined = garment.stitchPairs;
  for (const GarmentEdgeStitch& e : garment.edgeStitches) {
    joined.emplace_back(e.vertex, e.a);
    joined.emplace_back(e.vertex, e.b);
  }
  const collision::SelfIntersections found = collision::countSelfIntersections(x, garment.triangles, joined);
  QualityCheck c;
  c.name = "self_intersections";
  c.value = found.count;
  c.threshold = s.maxSelfIntersections;
  c.passed = c.value <= c.threshold;
  c.triangle = found.firstTriangle;
  c.otherTriangle = found.secondTriangle;
  if (found.count > 0)
    c.where = triangleName(garment, found.firstTriangle) + " and " + triangleName(garment, found.secondTriangle) +
              atPoint(triangleCentre(garment, x, found.firstTriangle));
  c.message = format("self_intersections: %d pairs of garment triangles cross (threshold %d)", found.count,
                     s.maxSelfIntersections) +
              (c.where.empty() ? std::string() : "; first: " + c.where);
  return c;
}

// The largest distance between two sewn points: a vertex and its partner across a seam, or a vertex and the point of
// the other side's edge it is sewn to (non-conforming seams).
QualityCheck seamGapCheck(const Garment& garment, const Eigen::MatrixX3d& x, const QualitySettings& s) {
  QualityCheck c;
  c.name = "seam_gap";
  c.threshold = s.maxSeamGap;
  int seam = -1, partner = -1;
  const auto consider = [&](int seamIndex, int v, int w, const Eigen::Vector3d& other) {
    const double gap = (x.row(v).transpose() - other).norm();
    if (c.vertex < 0 || gap > c.value || std::isnan(gap)) {
      c.value = gap;
      c.vertex = v;
      seam = seamIndex;
      partner = w;
    }
  };
  for (const GarmentStitch& st : garment.stitches) {
    for (int i = st.firstPair; i < st.firstPair + st.pairCount; ++i) {
      const auto [v, w] = garment.stitchPairs[i];
      consider(st.stitch, v, w, x.row(w).transpose());
    }
    for (int i = st.firstEdgeStitch; i < st.firstEdgeStitch + st.edgeStitchCount; ++i) {
      const GarmentEdgeStitch& e = garment.edgeStitches[i];
      const Eigen::Vector3d point = (1.0 - e.t) * x.row(e.a).transpose() + e.t * x.row(e.b).transpose();
      consider(st.stitch, e.vertex, e.t <= 0.5 ? e.a : e.b, point);
    }
  }
  c.passed = !(c.value > c.threshold);
  if (c.vertex >= 0)
    c.where = "seam " + std::to_string(seam) + ": " + vertexPlace(garment, x, c.vertex) + ", sewn to vertex " +
              std::to_string(partner) + panelOf(garment, garment.vertexPanel(partner));
  c.message =
      format("seam_gap: two sewn points %.1f mm apart (threshold %.1f mm), ", 1e3 * c.value, 1e3 * c.threshold) +
      (c.where.empty() ? std::string("no seams") : c.where);
  return c;
}

QualityCheck restCheck(const std::string& endStatus, const QualitySettings& s, const RestMeasures& rest) {
  QualityCheck c;
  c.name = "at_rest";
  c.value = endStatus == "AtRest" ? 1.0 : 0.0;
  c.threshold = s.requireRest ? 1.0 : 0.0;
  c.passed = c.value >= c.threshold;
  c.message = c.value > 0.0
                  ? std::string("at_rest: the run ended at rest")
                  : "at_rest: the run ended with " + (endStatus.empty() ? std::string("no status") : endStatus) +
                        ", not at rest" + (s.requireRest ? " (quality.require_rest)" : "");
  if (rest.forceRms >= 0.0)
    c.message += format("; unbalanced force %.3g %% of the weight RMS, %.3g %% at most; the last step moved %.3g mm "
                        "at most",
                        100.0 * rest.forceRms, 100.0 * rest.forceMax, 1e3 * rest.displacementMax);
  return c;
}

}  // namespace

const QualityCheck* QualityReport::find(std::string_view name) const {
  for (const QualityCheck& c : checks)
    if (c.name == name) return &c;
  return nullptr;
}

QualityReport checkDrapeQuality(const Garment& garment, const Eigen::MatrixX3d& positions,
                                const collision::AvatarCollider* collider, double contactThickness,
                                const std::string& endStatus, const QualitySettings& settings,
                                const RestMeasures& rest) {
  QualityReport report;
  report.checks.push_back(strainCheck(garment, positions, settings));
  if (collider) {
    colliderChecks(garment, positions, *collider, contactThickness, settings, report.checks);
    report.checks.push_back(outwardCheck(garment, positions, *collider, settings));
  }
  report.checks.push_back(selfIntersectionCheck(garment, positions, settings));
  report.checks.push_back(seamGapCheck(garment, positions, settings));
  report.checks.push_back(restCheck(endStatus, settings, rest));
  for (const QualityCheck& c : report.checks) report.passed = report.passed && c.passed;
  return report;
}

QualityReport checkDrapeQuality(const Simulation& simulation, const std::string& endStatus) {
  RestMeasures rest;
  if (simulation.steps() > 0) {
    const StepReport& last = simulation.lastStep();
    rest = {last.forceRms, last.forceMax, last.displacementMax};
  }
  return checkDrapeQuality(simulation.garment(), simulation.positions(), simulation.collider(),
                           simulation.contactThickness(), endStatus, qualitySettingsFrom(simulation.scene().settings),
                           rest);
}

}  // namespace drape
