// drape --info FILE: what a pattern, scene or avatar file contains.
#include <algorithm>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "commands.h"
#include "drape/avatar/avatar_loader.h"
#include "drape/pattern/dxf_aama.h"
#include "drape/pattern/edge_curve.h"
#include "drape/scene/pins.h"
#include "drape/sim/scene_garment.h"
#include "drape/sim/simulation.h"

namespace drape::app {
namespace {

std::string formatBox(const BoundingBox& b) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(3) << "min [" << b.min.x() << ", " << b.min.y() << ", " << b.min.z()
     << "] max [" << b.max.x() << ", " << b.max.y() << ", " << b.max.z() << "] size [" << b.size().x() << ", "
     << b.size().y() << ", " << b.size().z() << "] m";
  return os.str();
}

void describeMesh(const std::string& label, const std::string& file, const TriangleMesh& mesh, std::ostream& out) {
  out << label << ": " << file << "\n  vertices: " << mesh.vertexCount() << "\n  triangles: " << mesh.triangleCount()
      << "\n  bounding box: " << formatBox(boundsOf(mesh.vertices)) << "\n";
}

void describePattern(const Pattern& pattern, std::ostream& out) {
  size_t edges = 0;
  for (const auto& p : pattern.panels) edges += p.edges.size();
  out << "pattern: " << pattern.source << "\n  units per metre: " << pattern.unitsInMeter
      << "\n  panels: " << pattern.panels.size() << "\n  edges: " << edges << "\n  stitches: " << pattern.stitches.size()
      << "\n";
  for (const auto& p : pattern.panels) {
    double perimeter = 0;
    int curved = 0;
    for (size_t e = 0; e < p.edges.size(); ++e) {
      perimeter += edgeLength(p, static_cast<int>(e));
      curved += p.edges[e].curve.type != CurveType::Straight;
    }
    out << "    panel '" << p.name << "': " << p.vertices.size() << " vertices, " << p.edges.size() << " edges ("
        << curved << " curved), perimeter " << std::fixed << std::setprecision(3)
        << perimeter / pattern.unitsInMeter << " m" << std::defaultfloat;
    if (p.grainLine) out << ", grain line";
    if (!p.notches.empty()) out << ", " << p.notches.size() << " notches";
    if (!p.internalLines.empty()) out << ", " << p.internalLines.size() << " internal lines";
    out << "\n";
  }
}

void describeScene(const Scene& scene, std::ostream& out) {
  describePattern(scene.pattern, out);
  const MeshingOptions meshing = meshingOptions(scene);
  Diagnostics diagnostics;
  const Garment garment = buildSceneGarment(scene, &diagnostics);
  const auto pinned = resolvePins(scene, garment);
  out << "garment (target edge " << meshing.targetEdgeLength << " m):\n  vertices: " << garment.vertexCount()
      << "\n  triangles: " << garment.triangleCount() << "\n  stitch vertex pairs: " << garment.stitchPairs.size()
      << "\n  edge stitches (non-conforming seams): " << garment.edgeStitches.size()
      << "\n  pinned vertices: " << pinned.size() << "\n  bounding box: " << formatBox(boundsOf(garment.positions))
      << "\n";
  out << "fabric: " << scene.fabric.name << " (stretch " << scene.fabric.stretchWarp << "/" << scene.fabric.stretchWeft
      << " N/m, bend " << scene.fabric.bendWarp << "/" << scene.fabric.bendWeft << " N m, density "
      << scene.fabric.density << " kg/m^2)\n";
  for (const auto& [panel, fabric] : scene.panelFabrics) out << "  panel '" << panel << "': " << fabric.name << "\n";
  if (scene.hasAvatar()) describeMesh("avatar", scene.avatarFile.string(), scene.avatar, out);
  else out << "avatar: none\n";
  for (const auto& c : scene.colliders) describeMesh("collider", c.name, c.mesh, out);
  auto warnings = scene.diagnostics.warnings();
  warnings.insert(warnings.end(), diagnostics.warnings().begin(), diagnostics.warnings().end());
  out << "warnings: " << warnings.size() << "\n";
  for (const auto& w : warnings) out << "  " << w << "\n";
}

}  // namespace

int runInfo(const CliOptions& options, std::ostream& out) {
  const auto& file = options.scene.input;
  if (file.extension() == ".json" || isDxfFile(file)) {
    const Scene scene = loadScene(options.scene);
    if (!isPatternFile(file)) out << "scene: " << file.string() << "\n";
    describeScene(scene, out);
  } else {
    Diagnostics diagnostics;
    const double units =
        unitsInMeterFromName(options.scene.avatarUnits.empty() ? "m" : options.scene.avatarUnits);
    const TriangleMesh mesh = loadAvatar(file, units, &diagnostics);
    describeMesh("mesh", file.string(), mesh, out);
    for (const auto& w : diagnostics.warnings()) out << "  warning: " << w << "\n";
  }
  return 0;
}

}  // namespace drape::app
