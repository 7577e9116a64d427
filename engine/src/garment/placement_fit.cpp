#include "drape/garment/placement_fit.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "drape/avatar/body_landmarks.h"
#include "drape/collision/avatar_collider.h"
#include "drape/core/disjoint_sets.h"
#include "drape/core/input_error.h"

namespace drape {
namespace {

// Offsets between a group's features and the avatar's landmarks up to the first bound are a pattern's own ease and
// layout gaps (a neckline's height, a sleeve's gap from the armhole) or the landmarks' uncertainty, and are left
// alone; offsets beyond the second are corrected in full, and in between the correction grows linearly from 0 to
// the whole offset, so that the move is continuous in the offset.
constexpr double kLeaveOffset = 0.05, kCorrectOffset = 0.10;  // metres
constexpr double kLeaveAngle = 15.0, kCorrectAngle = 30.0;    // degrees
constexpr int kMaxPushSteps = 200;

enum class Region { Torso, Lower, Arm, Head, Unknown };

bool contains(const std::string& s, const char* word) {
  return s.find(word) != std::string::npos;
}

Region regionOfName(std::string name) {
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (contains(name, "sleeve") || contains(name, "cuff")) return Region::Arm;
  if (contains(name, "hood")) return Region::Head;
  if (contains(name, "skirt") || contains(name, "pant") || contains(name, "trouser") || contains(name, "leg") ||
      contains(name, "short") || contains(name, "waistband"))
    return Region::Lower;
  if (contains(name, "torso") || contains(name, "bodice") || contains(name, "collar") || contains(name, "neck") ||
      contains(name, "yoke"))
    return Region::Torso;
  return Region::Unknown;  // "front", "back", ...: decided by what it is sewn to and where it lies
}

// Panels sewn together in one region class move together: the arms (each side on its own), the head, and the body
// (torso, hips and legs, and panels of unknown names).
int regionClass(Region r, bool left) {
  switch (r) {
    case Region::Arm: return left ? 1 : 2;
    case Region::Head: return 3;
    default: return 0;
  }
}

// A group's region: a sleeve panel makes an arm, else a hood a head, else a torso panel a torso.
int priority(Region r) {
  switch (r) {
    case Region::Arm: return 0;
    case Region::Head: return 1;
    case Region::Torso: return 2;
    case Region::Lower: return 3;
    default: return 4;
  }
}

// The part of an offset of size n that is corrected (see kLeaveOffset).
double corrected(double n, double leave, double correct) {
  if (n <= leave) return 0.0;
  return n >= correct ? n : (n - leave) * correct / (correct - leave);
}

Eigen::Vector3d corrected(const Eigen::Vector3d& r) {
  const double n = r.norm();
  return n > 0 ? Eigen::Vector3d(r * (corrected(n, kLeaveOffset, kCorrectOffset) / n)) : Eigen::Vector3d::Zero();
}

struct Group {
  std::vector<int> panels;
  std::vector<int> vertices;
  Region region = Region::Unknown;
  bool left = false;
  BoundingBox bounds;
  // Rigid move: x -> rotation (x - pivot) + pivot + translation.
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

class Fitter {
 public:
  Fitter(const Pattern& pattern, Garment& garment, const BodyLandmarks& body)
      : m_pattern(pattern), m_garment(garment), m_body(body) {}

  void fitRegions() {
    buildGroups();
    // Body groups (torso, hips) first: a sleeve's target depends on where its torso's armhole ends.
    for (size_t g = 0; g < m_groups.size(); ++g)
      if (regionClass(m_groups[g].region, false) == 0) fitBody(static_cast<int>(g));
    for (size_t g = 0; g < m_groups.size(); ++g) {
      if (m_groups[g].region == Region::Arm) fitArm(static_cast<int>(g));
      if (m_groups[g].region == Region::Head) fitHead(static_cast<int>(g));
    }
    for (const Group& group : m_groups) {
      // A group left alone keeps its positions bit for bit.
      if (group.translation.isZero(0.0) && group.rotation.isIdentity(0.0)) continue;
      for (int v : group.vertices) {
        const Eigen::Vector3d x = m_garment.positions.row(v).transpose();
        m_garment.positions.row(v) = (group.rotation * (x - group.pivot) + group.pivot + group.translation).transpose();
      }
    }
  }

  // The arm group a panel belongs to, or -1.
  int armGroupOfPanel(int panel) const {
    const int g = m_groupOfPanel[panel];
    return m_groups[g].region == Region::Arm ? g : -1;
  }
  const BodyAxis& armAxis(int group) const { return m_groups[group].left ? m_body.leftArm : m_body.rightArm; }

 private:
  Eigen::Vector3d position(int v) const { return m_garment.positions.row(v).transpose(); }

  void buildGroups() {
    const int panels = static_cast<int>(m_pattern.panels.size());
    std::vector<std::vector<int>> vertices(panels);
    for (int v = 0; v < m_garment.vertexCount(); ++v) vertices[m_garment.vertexPanel(v)].push_back(v);
    std::vector<Region> region(panels);
    std::vector<bool> left(panels);
    for (int p = 0; p < panels; ++p) {
      region[p] = regionOfName(m_pattern.panels[p].name);
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int v : vertices[p]) c += position(v);
      if (!vertices[p].empty()) c /= static_cast<double>(vertices[p].size());
      left[p] = c.x() > m_body.neckCentre.x();
    }
    std::vector<int> parent(panels);
    for (int p = 0; p < panels; ++p) parent[p] = p;
    for (const Stitch& s : m_pattern.stitches) {
      const int a = s.a.panel, b = s.b.panel;
      if (regionClass(region[a], left[a]) == regionClass(region[b], left[b]))
        parent[findRoot(parent, a)] = findRoot(parent, b);
    }
    std::map<int, int> index;
    m_groupOfPanel.assign(panels, -1);
    for (int p = 0; p < panels; ++p) {
      auto [it, added] = index.emplace(findRoot(parent, p), static_cast<int>(m_groups.size()));
      if (added) m_groups.emplace_back();
      Group& g = m_groups[it->second];
      m_groupOfPanel[p] = it->second;
      g.panels.push_back(p);
      g.vertices.insert(g.vertices.end(), vertices[p].begin(), vertices[p].end());
      g.left = left[p];
      g.region = std::min(g.region, region[p], [](Region a, Region b) { return priority(a) < priority(b); });
      for (int v : vertices[p]) g.bounds.extend(position(v));
    }
    // A body group of unknown names dresses the torso when it reaches above the bust or has sleeves sewn on,
    // else the hips and legs.
    for (size_t g = 0; g < m_groups.size(); ++g) {
      Group& group = m_groups[g];
      if (group.region != Region::Unknown) continue;
      group.region = group.bounds.max.y() > m_body.bustHeight ? Region::Torso : Region::Lower;
      for (const Stitch& s : m_pattern.stitches)
        for (auto [mine, other] : {std::pair{s.a.panel, s.b.panel}, std::pair{s.b.panel, s.a.panel}})
          if (m_groupOfPanel[mine] == static_cast<int>(g) && region[other] == Region::Arm) group.region = Region::Torso;
    }
  }

  // Vertices of `group` on edges sewn to panels of group `other` (-1: any other group).
  std::vector<int> seamVertices(int group, int other) const {
    std::set<int> out;
    for (const Stitch& s : m_pattern.stitches)
      for (auto [mine, theirs] : {std::pair{s.a, s.b}, std::pair{s.b, s.a}}) {
        const int gm = m_groupOfPanel[mine.panel], gt = m_groupOfPanel[theirs.panel];
        if (gm == group && gt != group && (other < 0 || gt == other))
          for (int v : m_garment.edgeVertices[mine.panel][mine.edge]) out.insert(v);
      }
    return {out.begin(), out.end()};
  }
  // Vertices of `group` on edges sewn nowhere (a sleeve's cuff, a hem).
  std::vector<int> freeEdgeVertices(int group) const {
    std::set<std::pair<int, int>> sewn;
    for (const Stitch& s : m_pattern.stitches) {
      sewn.emplace(s.a.panel, s.a.edge);
      sewn.emplace(s.b.panel, s.b.edge);
    }
    std::vector<int> out;
    for (int p : m_groups[group].panels)
      for (size_t e = 0; e < m_garment.edgeVertices[p].size(); ++e)
        if (!sewn.count({p, static_cast<int>(e)}))
          out.insert(out.end(), m_garment.edgeVertices[p][e].begin(), m_garment.edgeVertices[p][e].end());
    return out;
  }
  // The highest of vertices, or -1 when there are none.
  int highest(const std::vector<int>& vertices) const {
    int best = -1;
    for (int v : vertices)
      if (best < 0 || m_garment.positions(v, 1) > m_garment.positions(best, 1)) best = v;
    return best;
  }
  const Eigen::Vector3d& shoulder(bool left) const { return left ? m_body.leftShoulder : m_body.rightShoulder; }

  // A torso is placed by the top ends of the armholes its sleeves are sewn to (the shoulder points of the body it
  // was made for), or without sleeves by its top edge, against the avatar's shoulder points; hips and legs by the
  // waistband against the waist. Sideways each is centred on the body's axis. Front to back the pattern's own
  // layout stays (GarmentCode lays front and back panels at depths of its own); the push out of the body below
  // takes care of depth.
  void fitBody(int g) {
    Group& group = m_groups[g];
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    const Eigen::Vector3d centre = group.bounds.center();
    if (group.region == Region::Torso) {
      const Eigen::Vector3d axis = m_body.centreAt(m_body.bustHeight);
      r.x() = axis.x() - centre.x();
      int sides = 0;
      double dy = 0.0;
      for (size_t a = 0; a < m_groups.size(); ++a) {
        if (m_groups[a].region != Region::Arm) continue;
        const int top = highest(seamVertices(g, static_cast<int>(a)));
        if (top < 0) continue;
        dy += shoulder(m_groups[a].left).y() - m_garment.positions(top, 1);
        ++sides;
      }
      const double shoulderY = 0.5 * (m_body.leftShoulder.y() + m_body.rightShoulder.y());
      r.y() = sides ? dy / sides : shoulderY - group.bounds.max.y();
    } else {
      const Eigen::Vector3d axis = m_body.centreAt(m_body.waistHeight);
      r = Eigen::Vector3d(axis.x() - centre.x(), m_body.waistHeight - group.bounds.max.y(), 0.0);
    }
    group.translation = corrected(r);
  }

  // A sleeve keeps its offset from the torso's armhole end (the seam's layout gap) while that end goes where the
  // torso went and the body's shoulder point is, and turns about its armhole's top point from its axis (armhole
  // centre to cuff centre) to the arm's.
  void fitArm(int g) {
    Group& group = m_groups[g];
    const std::vector<int> armhole = seamVertices(g, -1);
    const std::vector<int> cuff = freeEdgeVertices(g);
    Eigen::Vector3d capTop = group.bounds.center();
    Eigen::Vector3d target = shoulder(group.left);
    Eigen::Vector3d alongTorso = Eigen::Vector3d::Zero();
    if (!armhole.empty()) {
      capTop = position(highest(armhole));
      // The torso's armhole end this sleeve is sewn to, and where the torso's move took it.
      for (const Stitch& s : m_pattern.stitches)
        for (auto [mine, theirs] : {std::pair{s.a.panel, s.b.panel}, std::pair{s.b.panel, s.a.panel}})
          if (m_groupOfPanel[mine] == g && m_groupOfPanel[theirs] != g &&
              m_groups[m_groupOfPanel[theirs]].region != Region::Arm) {
            const int torso = m_groupOfPanel[theirs];
            const int end = highest(seamVertices(torso, g));
            if (end < 0) continue;
            const Eigen::Vector3d torsoEnd = position(end);
            target = shoulder(group.left) + (capTop - torsoEnd);
            alongTorso = m_groups[torso].translation;
          }
    }
    Eigen::Vector3d r = target - capTop;
    r.z() = 0.0;
    // An offset the fit leaves alone lets the sleeve follow its torso, so that the armhole seam keeps its layout.
    const Eigen::Vector3d own = corrected(r - alongTorso);
    group.translation = alongTorso + own;
    group.pivot = capTop;
    if (!armhole.empty() && !cuff.empty()) {
      Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
      for (int v : armhole) a += position(v);
      for (int v : cuff) b += position(v);
      a /= static_cast<double>(armhole.size());
      b /= static_cast<double>(cuff.size());
      const Eigen::Vector3d u = (b - a).normalized();
      const Eigen::Vector3d d = armAxis(g).direction;
      const double angle = std::acos(std::clamp(u.dot(d), -1.0, 1.0)) * 180.0 / M_PI;
      const double turn = corrected(angle, kLeaveAngle, kCorrectAngle);
      const Eigen::Vector3d axis = u.cross(d);
      if (turn > 0 && axis.norm() > 1e-9)
        group.rotation = Eigen::AngleAxisd(turn * M_PI / 180.0, axis.normalized()).toRotationMatrix();
    }
  }

  // A hood follows the torso it is sewn to.
  void fitHead(int g) {
    for (const Stitch& s : m_pattern.stitches)
      for (auto [mine, theirs] : {std::pair{s.a.panel, s.b.panel}, std::pair{s.b.panel, s.a.panel}})
        if (m_groupOfPanel[mine] == g && m_groups[m_groupOfPanel[theirs]].region == Region::Torso)
          m_groups[g].translation = m_groups[m_groupOfPanel[theirs]].translation;
  }

  const Pattern& m_pattern;
  Garment& m_garment;
  const BodyLandmarks& m_body;
  std::vector<Group> m_groups;
  std::vector<int> m_groupOfPanel;
};

// Moves each panel with vertices closer to the avatar than the clearance outward, rigidly, until it is clear:
// away from the arm's axis for a sleeve's panel, else horizontally away from the body's axis.
void pushPanelsOut(Garment& garment, const Fitter& fitter, const BodyLandmarks& body,
                   const collision::AvatarCollider& collider, double clearance) {
  const int panels = static_cast<int>(garment.panelNames.size());
  std::vector<std::vector<int>> vertices(panels);
  for (int v = 0; v < garment.vertexCount(); ++v) vertices[garment.vertexPanel(v)].push_back(v);
  for (int p = 0; p < panels; ++p) {
    if (vertices[p].empty()) continue;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : vertices[p]) c += garment.positions.row(v).transpose();
    c /= static_cast<double>(vertices[p].size());
    Eigen::Vector3d dir;
    const int arm = fitter.armGroupOfPanel(p);
    if (arm >= 0) {
      const BodyAxis& a = fitter.armAxis(arm);
      const Eigen::Vector3d q = c - a.origin;
      dir = q - a.direction * q.dot(a.direction);
    } else {
      dir = c - body.centreAt(c.y());
      dir.y() = 0.0;
    }
    for (int step = 0; step < kMaxPushSteps; ++step) {
      double deficit = 0.0;
      Eigen::Vector3d gradient = Eigen::Vector3d::Zero();
      for (int v : vertices[p]) {
        collision::SurfacePoint s;
        collider.closest(garment.positions.row(v).transpose(), s);
        const double d = clearance - s.signedDistance;
        if (d > 0) gradient += s.normal * d;
        deficit = std::max(deficit, d);
      }
      if (deficit <= 0) break;
      if (step == 0 && dir.norm() < 1e-3) dir = gradient;
      if (dir.norm() < 1e-12) break;
      const Eigen::Vector3d move = dir.normalized() * std::max(deficit, 0.002);
      for (int v : vertices[p]) garment.positions.row(v) += move.transpose();
    }
  }
}

}  // namespace

PlacementFitResult fitPlacementToAvatar(const Pattern& pattern, Garment& garment, const TriangleMesh& avatar,
                                        const PlacementFitOptions& options, Diagnostics* diagnostics) {
  PlacementFitResult result;
  if (garment.vertexCount() == 0 || avatar.triangleCount() == 0) return result;
  BodyLandmarks body;
  try {
    body = findBodyLandmarks(avatar);
  } catch (const InputError& e) {
    if (diagnostics)
      diagnostics->warn(pattern.source + ": placement: the pattern is placed as laid out, not fitted to the avatar (" +
                        e.what() + ")");
    return result;
  }
  const Eigen::MatrixX3d before = garment.positions;
  Fitter fitter(pattern, garment, body);
  fitter.fitRegions();
  const collision::AvatarCollider collider(avatar);
  pushPanelsOut(garment, fitter, body, collider, options.clearance);

  result.fitted = true;
  result.moves.resize(garment.panelNames.size());
  for (size_t p = 0; p < garment.panelNames.size(); ++p) result.moves[p].panel = garment.panelNames[p];
  for (int v = 0; v < garment.vertexCount(); ++v) {
    double& d = result.moves[garment.vertexPanel(v)].distance;
    d = std::max(d, (garment.positions.row(v) - before.row(v)).norm());
  }
  if (diagnostics)
    for (const PanelPlacementMove& m : result.moves)
      if (m.distance > options.warnDistance) {
        char text[64];
        std::snprintf(text, sizeof text, "%.1f cm", 100.0 * m.distance);
        diagnostics->warn(pattern.source + ": placement: panel '" + m.panel + "' moved " + text +
                          " to fit the avatar: the pattern was laid out for another body");
      }
  return result;
}

}  // namespace drape
