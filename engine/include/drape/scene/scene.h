#pragma once
// A scene: the pattern, the avatar and generated colliders, the fabrics, the pins and every setting.
// Loaded from a scene file (docs/FORMATS.md) or assembled from a bare pattern plus command-line options.
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "drape/core/diagnostics.h"
#include "drape/fabric/fabric.h"
#include "drape/geometry/triangle_mesh.h"
#include "drape/pattern/pattern.h"
#include "drape/scene/implementation.h"
#include "drape/scene/settings.h"

namespace drape {

// A collider the scene generates itself (the tablecloth's sphere), in metres.
struct Collider {
  std::string name;  // "sphere", "box"
  TriangleMesh mesh;
};

// Prescribed motion of pinned vertices (the twisting square's rotating side). Between start and end (s) the
// vertices turn by angle (radians, right-handed about axis) around the line through center and translate by
// translation (m), both linear in time; before start they hold their initial positions, after end the final ones.
struct PinMotion {
  double start = 0.0;
  double end = 0.0;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit
  double angle = 0.0;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  // Where a vertex that starts at initial (metres) is at scene time t (s).
  Eigen::Vector3d at(const Eigen::Vector3d& initial, double t) const;
};

// A set of garment vertices held in place: a whole panel edge (by index or label), every vertex whose placed
// position lies in an axis-aligned region (metres), or garment vertices by index (pins set in the GUI; indices
// of the mesh that the scene's mesh settings give). Optionally moving.
struct PinSpec {
  std::string panel;      // empty for a region or vertex pin
  int edge = -1;          // edge index, or -1 when edgeLabel is used
  std::string edgeLabel;  // edge "label" from the pattern file
  bool byRegion = false;
  BoundingBox region;
  std::vector<int> vertices;  // garment vertex indices (a vertex pin when non-empty)
  // Vertex pin only, optional ("at"): the placed position (metres, Garment::positions) each entry of vertices was
  // saved at, same order; when given the position decides which vertex is pinned (pins.h, pinVertices).
  std::vector<Eigen::Vector3d> at;
  bool moving = false;
  PinMotion motion;   // when moving
  std::string where;  // "scene.json: pin 2", for messages
};

struct Scene {
  std::filesystem::path file;         // the scene file, or the bare pattern file
  std::filesystem::path patternFile;  // resolved
  std::filesystem::path avatarFile;   // resolved; empty when the scene has no avatar
  Settings settings;
  Pattern pattern;
  TriangleMesh avatar;              // no triangles when the scene has no avatar
  std::vector<Collider> colliders;  // generated primitives
  Fabric fabric;                    // default fabric of every panel, overrides applied
  std::map<std::string, Fabric> panelFabrics;  // panel name -> fabric, where it differs from the default
  std::vector<PinSpec> pins;
  Diagnostics diagnostics;          // warnings from every loader
  Implementation implementation;    // set by benchmarks and tests, never by a scene file

  bool hasAvatar() const { return avatar.triangleCount() > 0; }
  const Fabric& fabricOfPanel(const std::string& panel) const {
    auto it = panelFabrics.find(panel);
    return it == panelFabrics.end() ? fabric : it->second;
  }
};

// What a caller asks for: a scene file or a bare pattern, plus command-line choices applied over it.
struct SceneRequest {
  std::filesystem::path input;  // scene .json or pattern .json
  std::string avatarFile;       // --avatar (relative to the working directory)
  std::string avatarUnits;      // --avatar-units m|cm|mm|in
  std::string fabricPreset;     // --fabric
  std::vector<std::pair<std::string, std::string>> overrides;  // --set key=value, applied last
};

// Loads and validates everything the scene names; throws InputError naming the file and the element.
Scene loadScene(const SceneRequest& request);

// The sections of a scene file whose leaves are settings ("mesh": {"target_edge_length": 0.02} is the setting
// mesh.target_edge_length), in the order the format lists them.
const std::vector<std::string>& sceneSettingSections();

// True when file holds a sewing pattern (a "pattern" object with panels) rather than a scene.
bool isPatternFile(const std::filesystem::path& file);

}  // namespace drape
