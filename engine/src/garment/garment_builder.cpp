// Pattern -> Garment: edge sampling shared by stitched edges, per-panel
// meshing, placement, stitch pairs.
#include "drape/garment/garment_builder.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <sstream>

#include "drape/core/disjoint_sets.h"
#include "drape/core/input_error.h"
#include "drape/garment/panel_mesher.h"
#include "drape/pattern/edge_curve.h"

namespace drape {
namespace {

// Flat index of (panel, edge) over all panels' edges.
struct EdgeIndexer {
  std::vector<int> first;  // first flat index of each panel's edges
  int total = 0;
  explicit EdgeIndexer(const Pattern& pattern) {
    for (const Panel& panel : pattern.panels) {
      first.push_back(total);
      total += static_cast<int>(panel.edges.size());
    }
  }
  int operator()(int panel, int edge) const { return first[panel] + edge; }
};

std::string panelContext(const Pattern& pattern, int p) {
  return pattern.source + ": panel '" + pattern.panels[p].name + "'";
}

void checkStitchSide(const Pattern& pattern, int s, const StitchSide& side, const char* which) {
  const bool panelOk = side.panel >= 0 && side.panel < static_cast<int>(pattern.panels.size());
  if (panelOk && side.edge >= 0 && side.edge < static_cast<int>(pattern.panels[side.panel].edges.size())) return;
  std::ostringstream msg;
  msg << pattern.source << ": stitch " << s << " side " << which << ": ";
  if (!panelOk) {
    msg << "panel " << side.panel << " out of range (pattern has " << pattern.panels.size() << " panels)";
  } else {
    msg << "edge " << side.edge << " out of range (panel '" << pattern.panels[side.panel].name << "' has "
        << pattern.panels[side.panel].edges.size() << " edges)";
  }
  throw InputError(msg.str());
}

// Smallest rest area of a mesh triangle, m^2. The cloth models divide by it (the Newton membrane refuses twice the
// area at or below 1e-14 m^2, the preview leaves out triangles at or below 1e-14 m^2); a panel that passed the
// pattern checks can still have a corner too sharp to mesh, and that is the file's problem, so it is refused here
// naming the panel rather than as an internal error of the solver.
constexpr double kMinTriangleArea = 1e-14;

void checkRestAreas(const PanelMesh& mesh, const std::string& context) {
  for (Eigen::Index t = 0; t < mesh.triangles.rows(); ++t) {
    const Eigen::Vector2d a = mesh.vertices.row(mesh.triangles(t, 0)).transpose();
    const Eigen::Vector2d ab = mesh.vertices.row(mesh.triangles(t, 1)).transpose() - a;
    const Eigen::Vector2d ac = mesh.vertices.row(mesh.triangles(t, 2)).transpose() - a;
    const double area = 0.5 * std::abs(ab.x() * ac.y() - ab.y() * ac.x());
    if (area > kMinTriangleArea) continue;
    std::ostringstream msg;
    msg << context << ": meshing gives triangle " << t << " an area of " << area << " m^2 (it must exceed "
        << kMinTriangleArea << " m^2): an outline corner too sharp or a strip too thin to mesh";
    throw InputError(msg.str());
  }
}

// Number of segments for every edge (flat index): round(length / target of its
// panel), at least 1; with conforming seams, all edges joined by stitches
// (directly or through a chain) share the largest count among them.
std::vector<int> segmentCounts(const Pattern& pattern, const EdgeIndexer& index,
                               const std::vector<double>& targetFileUnits, bool conforming) {
  std::vector<int> own(index.total);
  for (int p = 0; p < static_cast<int>(pattern.panels.size()); ++p) {
    for (int e = 0; e < static_cast<int>(pattern.panels[p].edges.size()); ++e) {
      const double segments = std::round(edgeLength(pattern.panels[p], e) / targetFileUnits[p]);
      own[index(p, e)] = static_cast<int>(std::max(1.0, segments));
    }
  }
  if (!conforming) return own;
  std::vector<int> parent(index.total);
  std::iota(parent.begin(), parent.end(), 0);
  for (const Stitch& s : pattern.stitches) {
    const int a = findRoot(parent, index(s.a.panel, s.a.edge));
    const int b = findRoot(parent, index(s.b.panel, s.b.edge));
    parent[a] = b;
  }
  std::vector<int> groupCount(index.total, 0);
  for (int i = 0; i < index.total; ++i) {
    const int r = findRoot(parent, i);
    groupCount[r] = std::max(groupCount[r], own[i]);
  }
  std::vector<int> counts(index.total);
  for (int i = 0; i < index.total; ++i) counts[i] = groupCount[findRoot(parent, i)];
  return counts;
}

// The closed outline of panel p from its sampled edges, and for each edge the
// outline indices of its points from start to end (the last edge ends at index
// 0).
std::vector<Eigen::Vector2d> sampleOutline(const Pattern& pattern, int p, const std::vector<int>& counts,
                                           const EdgeIndexer& index, std::vector<std::vector<int>>& edgePoints) {
  const Panel& panel = pattern.panels[p];
  const int edgeCount = static_cast<int>(panel.edges.size());
  if (edgeCount < 2) {
    throw InputError(panelContext(pattern, p) + ": has " + std::to_string(edgeCount) +
                     " edges, a closed outline needs at least 2");
  }
  std::vector<Eigen::Vector2d> outline;
  edgePoints.assign(edgeCount, {});
  for (int e = 0; e < edgeCount; ++e) {
    const int next = (e + 1) % edgeCount;
    if (panel.edges[e].end != panel.edges[next].start) {
      std::ostringstream msg;
      msg << panelContext(pattern, p) << " edge " << e << ": ends at vertex " << panel.edges[e].end << " but edge "
          << next << " starts at vertex " << panel.edges[next].start << " (outline not closed)";
      throw InputError(msg.str());
    }
    const std::vector<Eigen::Vector2d> pts = sampleEdge(panel, e, counts[index(p, e)]);
    const int start = static_cast<int>(outline.size());
    for (size_t k = 0; k + 1 < pts.size(); ++k) {
      edgePoints[e].push_back(start + static_cast<int>(k));
      outline.push_back(pts[k]);
    }
    edgePoints[e].push_back(-1);  // end point: the next edge's first point, fixed below
  }
  for (int e = 0; e < edgeCount; ++e) edgePoints[e].back() = edgePoints[(e + 1) % edgeCount].front();
  return outline;
}

// Non-conforming seam (pd-dd section 4.4): every point of the side with more points (fine) is sewn to the point
// at the same arc-length fraction of the other side (coarse), on one of its segments. Both sides are sampled evenly
// by arc length; the sides run in opposite directions along the seam unless rightWrong.
void sewToEdges(const std::vector<int>& fine, const std::vector<int>& coarse, bool reversed,
                std::vector<GarmentEdgeStitch>& out) {
  const int nf = static_cast<int>(fine.size()) - 1, nc = static_cast<int>(coarse.size()) - 1;
  for (int k = 0; k <= nf; ++k) {
    const double s = static_cast<double>(reversed ? nf - k : k) / nf * nc;  // position along coarse, in segments
    const int seg = std::clamp(static_cast<int>(std::floor(s)), 0, nc - 1);
    const double t = std::clamp(s - seg, 0.0, 1.0);
    const int a = coarse[seg], b = coarse[seg + 1];
    if (fine[k] == a || fine[k] == b) continue;  // a corner shared by both sides (a dart's tip): already joined
    out.push_back({fine[k], a, b, t});
  }
}

// Twice the signed area of a closed polygon (positive when counter-clockwise).
double signedArea(const std::vector<Eigen::Vector2d>& polygon) {
  double sum = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    sum += a.x() * b.y() - b.x() * a.y();
  }
  return sum;
}

}  // namespace

// GarmentCode (pygarment Panel.assembly) writes the rotation as scipy's
// as_euler('XYZ'): intrinsic rotations about x, then the new y, then the new z,
// i.e. R = Rx * Ry * Rz.
Eigen::Vector3d placePanelPoint(const Panel& panel, const Eigen::Vector2d& p, double unitsInMeter) {
  const Eigen::Vector3d rad = panel.rotationDeg * (std::numbers::pi / 180.0);
  const Eigen::Matrix3d r =
      (Eigen::AngleAxisd(rad.x(), Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(rad.y(), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(rad.z(), Eigen::Vector3d::UnitZ()))
          .toRotationMatrix();
  return (r * Eigen::Vector3d(p.x(), p.y(), 0.0) + panel.translation) / unitsInMeter;
}

Garment buildGarment(const Pattern& pattern, const MeshingOptions& options, Diagnostics* diagnostics) {
  const double target = options.targetEdgeLength;
  if (!std::isfinite(target) || target <= 0.0) {
    std::ostringstream msg;
    msg << pattern.source << ": target edge length must be positive (got " << target << " m)";
    throw InputError(msg.str());
  }
  if (!std::isfinite(pattern.unitsInMeter) || pattern.unitsInMeter <= 0.0) {
    std::ostringstream msg;
    msg << pattern.source << ": units_in_meter must be positive (got " << pattern.unitsInMeter << ")";
    throw InputError(msg.str());
  }
  if (pattern.panels.empty()) throw InputError(pattern.source + ": pattern has no panels");
  for (size_t s = 0; s < pattern.stitches.size(); ++s) {
    checkStitchSide(pattern, static_cast<int>(s), pattern.stitches[s].a, "a");
    checkStitchSide(pattern, static_cast<int>(s), pattern.stitches[s].b, "b");
  }

  // Target edge length per panel, metres.
  std::vector<double> panelTarget(pattern.panels.size(), target);
  for (const auto& entry : options.panelTargetEdgeLength) {
    const std::string& name = entry.first;
    const double length = entry.second;
    const auto it = std::find_if(pattern.panels.begin(), pattern.panels.end(),
                                 [&name](const Panel& panel) { return panel.name == name; });
    std::ostringstream msg;
    if (it == pattern.panels.end()) {
      msg << pattern.source << ": target edge length given for panel '" << name << "', which the pattern lacks";
      throw InputError(msg.str());
    }
    if (!std::isfinite(length) || length <= 0.0) {
      msg << pattern.source << ": panel '" << name << "': target edge length must be positive (got " << length
          << " m)";
      throw InputError(msg.str());
    }
    panelTarget[it - pattern.panels.begin()] = length;
  }
  std::vector<double> panelTargetFileUnits(panelTarget.size());
  for (size_t p = 0; p < panelTarget.size(); ++p) panelTargetFileUnits[p] = panelTarget[p] * pattern.unitsInMeter;

  const EdgeIndexer index(pattern);
  const std::vector<int> counts = segmentCounts(pattern, index, panelTargetFileUnits, options.conformingSeams);
  const double toMetres = 1.0 / pattern.unitsInMeter;

  // Mesh every panel (in metres) and stack the results.
  const int panelCount = static_cast<int>(pattern.panels.size());
  std::vector<PanelMesh> meshes(panelCount);
  std::vector<std::vector<std::vector<int>>> edgePoints(panelCount);
  Eigen::Index vertexTotal = 0, triangleTotal = 0;
  for (int p = 0; p < panelCount; ++p) {
    std::vector<Eigen::Vector2d> outline = sampleOutline(pattern, p, counts, index, edgePoints[p]);
    for (Eigen::Vector2d& q : outline) q *= toMetres;
    meshes[p] = meshPanel(outline, panelTarget[p], panelContext(pattern, p));
    checkRestAreas(meshes[p], panelContext(pattern, p));
    // The mesher winds every triangle counter-clockwise in the plane; a clockwise outline marks the panel's
    // other side as its outside, so its triangles turn over with it.
    if (signedArea(outline) < 0.0) meshes[p].triangles.col(1).swap(meshes[p].triangles.col(2));
    vertexTotal += meshes[p].vertices.rows();
    triangleTotal += meshes[p].triangles.rows();
  }

  Garment g;
  g.rest.resize(vertexTotal, 2);
  g.positions.resize(vertexTotal, 3);
  g.vertexPanel.resize(vertexTotal);
  g.triangles.resize(triangleTotal, 3);
  g.trianglePanel.resize(triangleTotal);
  g.edgeVertices.resize(panelCount);
  Eigen::Index v0 = 0, f0 = 0;
  for (int p = 0; p < panelCount; ++p) {
    const Panel& panel = pattern.panels[p];
    const PanelMesh& m = meshes[p];
    g.panelNames.push_back(panel.name);
    const Eigen::Index nv = m.vertices.rows(), nf = m.triangles.rows();
    g.rest.middleRows(v0, nv) = m.vertices;
    for (Eigen::Index i = 0; i < nv; ++i) {
      // placePanelPoint takes file units; the mesh is in metres.
      g.positions.row(v0 + i) =
          (placePanelPoint(panel, m.vertices.row(i).transpose() * pattern.unitsInMeter, pattern.unitsInMeter) +
           options.placementOffset)
              .transpose();
    }
    g.vertexPanel.segment(v0, nv).setConstant(p);
    g.triangles.middleRows(f0, nf) = m.triangles.array() + static_cast<int>(v0);
    g.trianglePanel.segment(f0, nf).setConstant(p);
    for (const std::vector<int>& pts : edgePoints[p]) {
      std::vector<int> global(pts.size());
      for (size_t k = 0; k < pts.size(); ++k) global[k] = pts[k] + static_cast<int>(v0);
      g.edgeVertices[p].push_back(std::move(global));
    }
    v0 += nv;
    f0 += nf;
  }
  g.uvs = g.rest;
  // The material frame's warp runs along a panel's grain line when the pattern gives one: its rest coordinates
  // turn so that the grain becomes +x. The uvs keep the panel as cut.
  for (int p = 0; p < panelCount; ++p) {
    const auto& grain = pattern.panels[static_cast<size_t>(p)].grainLine;
    if (!grain) continue;
    const Eigen::Vector2d d = ((*grain)[1] - (*grain)[0]).normalized();
    if (!d.allFinite()) continue;
    Eigen::Matrix2d turn;
    turn << d.x(), d.y(), -d.y(), d.x();
    for (Eigen::Index v = 0; v < vertexTotal; ++v)
      if (g.vertexPanel(v) == p) g.rest.row(v) = (turn * g.rest.row(v).transpose()).transpose();
  }

  // Stitch pairs: rightWrong false pairs a's k-th point with b's (n-k)-th
  // (edges run in opposite directions along the seam), true pairs k with k.
  // Sides sampled with different counts (non-conforming) become edge stitches.
  for (size_t s = 0; s < pattern.stitches.size(); ++s) {
    const Stitch& st = pattern.stitches[s];
    const std::vector<int>& a = g.edgeVertices[st.a.panel][st.a.edge];
    const std::vector<int>& b = g.edgeVertices[st.b.panel][st.b.edge];
    GarmentStitch gs;
    gs.stitch = static_cast<int>(s);
    gs.firstPair = static_cast<int>(g.stitchPairs.size());
    gs.firstEdgeStitch = static_cast<int>(g.edgeStitches.size());
    if (a.size() == b.size()) {
      gs.pairCount = static_cast<int>(a.size());
      const int n = static_cast<int>(a.size()) - 1;
      for (int k = 0; k <= n; ++k) g.stitchPairs.emplace_back(a[k], st.rightWrong ? b[k] : b[n - k]);
    } else {
      const bool aFiner = a.size() > b.size();
      sewToEdges(aFiner ? a : b, aFiner ? b : a, !st.rightWrong, g.edgeStitches);
      gs.edgeStitchCount = static_cast<int>(g.edgeStitches.size()) - gs.firstEdgeStitch;
    }
    g.stitches.push_back(gs);
  }
  if (diagnostics) {
    // An edge sewn in more than one stitch gets one vertex paired several
    // times; usually a file mistake.
    std::vector<int> uses(index.total, 0);
    for (const Stitch& st : pattern.stitches) {
      ++uses[index(st.a.panel, st.a.edge)];
      ++uses[index(st.b.panel, st.b.edge)];
    }
    for (int p = 0; p < panelCount; ++p) {
      for (int e = 0; e < static_cast<int>(pattern.panels[p].edges.size()); ++e) {
        if (uses[index(p, e)] > 1) {
          diagnostics->warn(panelContext(pattern, p) + " edge " + std::to_string(e) + ": used in " +
                            std::to_string(uses[index(p, e)]) + " stitches");
        }
      }
    }
  }
  return g;
}

}  // namespace drape
