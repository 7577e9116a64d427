#include "drape/avatar/body_landmarks.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "drape/core/disjoint_sets.h"
#include "drape/core/input_error.h"

namespace drape {
namespace {

// Horizontal slices of the whole body, bottom to top.
struct Level {
  double y = 0.0;
  std::vector<SliceComponent> pieces;
};

// The piece whose x range contains x and is longest (the torso or the neck at that level), or nullptr.
const SliceComponent* pieceAround(const Level& level, double x) {
  const SliceComponent* best = nullptr;
  for (const SliceComponent& c : level.pieces)
    if (c.bounds.min.x() <= x && x <= c.bounds.max.x() && (!best || c.length > best->length)) best = &c;
  return best;
}

// Least-squares line through points: mean and principal direction.
BodyAxis fitLine(const std::vector<Eigen::Vector3d>& points) {
  BodyAxis axis;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  axis.origin = mean;
  axis.direction = eig.eigenvectors().col(2).normalized();
  return axis;
}

// Moves the axis origin along the line to where its coordinate `coord` equals value.
void slideOrigin(BodyAxis& axis, int coord, double value) {
  const double d = axis.direction[coord];
  if (std::abs(d) > 1e-6) axis.origin += axis.direction * ((value - axis.origin[coord]) / d);
}

// Sum of squared residuals of the least-squares line y(x) through samples [first, last).
double lineError(const std::vector<Eigen::Vector2d>& s, size_t first, size_t last) {
  const double n = static_cast<double>(last - first);
  double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
  for (size_t i = first; i < last; ++i) {
    sx += s[i].x();
    sy += s[i].y();
    sxx += s[i].x() * s[i].x();
    sxy += s[i].x() * s[i].y();
    syy += s[i].y() * s[i].y();
  }
  const double vxx = sxx - sx * sx / n, vxy = sxy - sx * sy / n, vyy = syy - sy * sy / n;
  return vxx > 0 ? std::max(0.0, vyy - vxy * vxy / vxx) : vyy;
}

// Slope dy/dx of the least-squares line through samples [first, last).
double lineSlope(const std::vector<Eigen::Vector2d>& s, size_t first, size_t last) {
  const double n = static_cast<double>(last - first);
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = first; i < last; ++i) {
    sx += s[i].x();
    sy += s[i].y();
    sxx += s[i].x() * s[i].x();
    sxy += s[i].x() * s[i].y();
  }
  const double vxx = sxx - sx * sx / n;
  return vxx > 0 ? (sxy - sx * sy / n) / vxx : 0.0;
}

// The shoulder point on one side (sign +1: left, +x): the corner of the body's top outline seen from the front (the
// top of each vertical slice from the side of the neck outwards), where the shoulder's gentle slope turns into the
// arm's: near the break of the best two-line fit of the outline, at the start of the arm's run.
Eigen::Vector3d shoulderPoint(const TriangleMesh& mesh, double neckSide, double neckHeight, double sign,
                              double height) {
  std::vector<Eigen::Vector2d> outline;  // (distance from the neck side, top y)
  std::vector<Eigen::Vector3d> tops;
  const double step = 0.005 * height;
  for (double d = step; d <= 0.25 * height; d += step) {
    const double x = neckSide + sign * d;
    const std::vector<SliceComponent> pieces = sliceMesh(mesh, 0, x);
    // The highest piece below the neck (the head, wider than the neck, is cut apart from the shoulders).
    const SliceComponent* top = nullptr;
    for (const SliceComponent& c : pieces)
      if (c.centroid.y() < neckHeight && (!top || c.bounds.max.y() > top->bounds.max.y())) top = &c;
    if (!top) break;
    outline.emplace_back(d, top->bounds.max.y());
    tops.emplace_back(x, top->bounds.max.y(), top->centroid.z());
  }
  if (outline.size() < 8) throw InputError("avatar: no shoulder found beside the neck (is it a standing body, y up?)");
  size_t best = 4;
  double bestError = std::numeric_limits<double>::infinity();
  for (size_t i = 4; i + 4 <= outline.size(); ++i) {
    const double e = lineError(outline, 0, i + 1) + lineError(outline, i, outline.size());
    if (e < bestError) bestError = e, best = i;
  }
  // The corner: from the lines' break inwards, the start of the run of samples where the outline falls more (an
  // A-pose) or less (a T-pose) steeply than halfway (in angle) between the two lines' slopes.
  const double inner = std::atan(-lineSlope(outline, 0, best + 1));
  const double outer = std::atan(-lineSlope(outline, best, outline.size()));
  const double corner = std::tan(0.5 * (inner + outer));
  auto fall = [&](size_t i) { return (outline[i - 1].y() - outline[i].y()) / (outline[i].x() - outline[i - 1].x()); };
  if (outer > inner)
    while (best > 1 && fall(best) > corner) --best;
  else
    while (best > 1 && fall(best) < corner) --best;
  return tops[best];
}

// The arm's axis on one side: a line through the centroids of the vertical slices of the arm beyond the shoulder
// point (the highest piece of each slice), direction away from the body.
BodyAxis armAxis(const TriangleMesh& mesh, const Eigen::Vector3d& shoulder, double sign, double height, double crotch) {
  std::vector<Eigen::Vector3d> centres;
  const double step = 0.005 * height;
  for (double d = 0.03 * height; d <= 0.2 * height; d += step) {
    const std::vector<SliceComponent> pieces = sliceMesh(mesh, 0, shoulder.x() + sign * d);
    const SliceComponent* arm = nullptr;
    for (const SliceComponent& c : pieces)
      if (!arm || c.centroid.y() > arm->centroid.y()) arm = &c;
    if (!arm || arm->centroid.y() < crotch) break;
    centres.push_back(arm->centroid);
  }
  if (centres.size() < 4) throw InputError("avatar: no arm found beyond the shoulder");
  BodyAxis axis = fitLine(centres);
  if (axis.direction.x() * sign < 0) axis.direction = -axis.direction;
  slideOrigin(axis, 0, shoulder.x());
  return axis;
}

}  // namespace

std::vector<SliceComponent> sliceMesh(const TriangleMesh& mesh, int axis, double value) {
  std::unordered_map<std::uint64_t, int> node;  // mesh edge -> node
  std::vector<int> parent;
  struct Segment {
    int node;
    Eigen::Vector3d a, b;
  };
  std::vector<Segment> segments;
  auto nodeOf = [&](int i, int j) {
    const std::uint64_t key =
        (static_cast<std::uint64_t>(std::min(i, j)) << 32) | static_cast<std::uint32_t>(std::max(i, j));
    auto [it, added] = node.emplace(key, static_cast<int>(parent.size()));
    if (added) parent.push_back(it->second);
    return it->second;
  };
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    int v[3];
    double s[3];
    for (int k = 0; k < 3; ++k) {
      v[k] = mesh.triangles(f, k);
      s[k] = mesh.vertices(v[k], axis) - value;
    }
    const bool above[3] = {s[0] >= 0, s[1] >= 0, s[2] >= 0};
    if (above[0] == above[1] && above[1] == above[2]) continue;
    Eigen::Vector3d p[2];
    int n[2];
    int count = 0;
    for (int k = 0; k < 3 && count < 2; ++k) {
      const int a = k, b = (k + 1) % 3;
      if (above[a] == above[b]) continue;
      const double t = s[a] / (s[a] - s[b]);
      p[count] =
          mesh.vertices.row(v[a]).transpose() + t * (mesh.vertices.row(v[b]) - mesh.vertices.row(v[a])).transpose();
      n[count] = nodeOf(v[a], v[b]);
      ++count;
    }
    const int ra = findRoot(parent, n[0]), rb = findRoot(parent, n[1]);
    if (ra != rb) parent[ra] = rb;
    segments.push_back({n[0], p[0], p[1]});
  }
  std::unordered_map<int, size_t> index;
  std::vector<SliceComponent> pieces;
  for (const Segment& s : segments) {
    const int root = findRoot(parent, s.node);
    auto [it, added] = index.emplace(root, pieces.size());
    if (added) pieces.emplace_back();
    SliceComponent& c = pieces[it->second];
    const double len = (s.b - s.a).norm();
    c.length += len;
    c.centroid += 0.5 * len * (s.a + s.b);
    c.bounds.extend(s.a);
    c.bounds.extend(s.b);
  }
  for (SliceComponent& c : pieces)
    if (c.length > 0) c.centroid /= c.length;
  std::sort(pieces.begin(), pieces.end(),
            [](const SliceComponent& a, const SliceComponent& b) { return a.length > b.length; });
  return pieces;
}

Eigen::Vector3d BodyLandmarks::centreAt(double y) const {
  const std::pair<double, Eigen::Vector3d> knots[] = {
      {hipHeight, hipCentre}, {waistHeight, waistCentre}, {bustHeight, bustCentre}, {neckHeight, neckCentre}};
  Eigen::Vector3d c = knots[0].second;
  if (y <= knots[0].first) return {c.x(), y, c.z()};
  for (int i = 0; i + 1 < 4; ++i) {
    const auto& [y0, c0] = knots[i];
    const auto& [y1, c1] = knots[i + 1];
    if (y <= y1 && y1 > y0) {
      c = c0 + (c1 - c0) * ((y - y0) / (y1 - y0));
      return {c.x(), y, c.z()};
    }
  }
  c = knots[3].second;
  return {c.x(), y, c.z()};
}

BodyLandmarks findBodyLandmarks(const TriangleMesh& mesh) {
  if (mesh.triangleCount() == 0) throw InputError("avatar: no triangles to find landmarks on");
  BodyLandmarks L;
  const BoundingBox box = boundsOf(mesh.vertices);
  L.floor = box.min.y();
  L.height = box.max.y() - box.min.y();
  Eigen::Index top = 0;
  mesh.vertices.col(1).maxCoeff(&top);
  L.headTop = mesh.vertices.row(top).transpose();
  const double H = L.height;
  const int count = 400;
  std::vector<Level> levels(count);
  for (int k = 0; k < count; ++k) {
    levels[k].y = L.floor + (k + 0.5) * H / count;
    levels[k].pieces = sliceMesh(mesh, 1, levels[k].y);
  }
  auto levelAt = [&](double fraction) { return std::clamp(static_cast<int>(fraction * count), 0, count - 1); };
  const double cx = L.headTop.x();

  // Neck: the narrowest piece around the head's axis between 75 % and 95 % of the height.
  int neck = -1;
  double neckLength = std::numeric_limits<double>::infinity();
  for (int k = levelAt(0.75); k <= levelAt(0.95); ++k) {
    const SliceComponent* c = pieceAround(levels[k], cx);
    if (c && c->length < neckLength) neckLength = c->length, neck = k;
  }
  if (neck < 0) throw InputError("avatar: no neck found (is it a standing body, y up?)");
  const SliceComponent& neckPiece = *pieceAround(levels[neck], cx);
  L.neckHeight = levels[neck].y;
  L.neckCentre = neckPiece.centroid;
  const double axisX = L.neckCentre.x();

  // Armpit: going down from the neck, the first level where the piece around the axis loses the arms (its width
  // drops to under three quarters of the level above).
  int armpit = -1;
  for (int k = neck - 1; k > levelAt(0.4); --k) {
    const SliceComponent* above = pieceAround(levels[k + 1], axisX);
    const SliceComponent* here = pieceAround(levels[k], axisX);
    if (above && here && here->bounds.size().x() < 0.75 * above->bounds.size().x()) {
      armpit = k;
      break;
    }
  }
  if (armpit < 0) throw InputError("avatar: no armpit found (the arms never part from the torso)");
  L.armpitHeight = levels[armpit].y;

  // Crotch: going down from the armpit, the first level with no piece around the axis (the legs apart).
  int crotch = -1;
  for (int k = armpit - 1; k > 0; --k)
    if (!pieceAround(levels[k], axisX)) {
      crotch = k;
      break;
    }
  if (crotch < 0) throw InputError("avatar: no crotch found (the legs never part)");
  L.crotchHeight = levels[crotch].y;

  // Girth levels on the torso piece's contour length.
  auto torso = [&](int k) { return pieceAround(levels[k], axisX); };
  auto extreme = [&](int from, int to, bool widest) {
    int best = -1;
    for (int k = std::max(from, crotch + 1); k <= std::min(to, armpit - 1); ++k) {
      const SliceComponent* c = torso(k);
      if (c && (best < 0 || (widest ? c->length > torso(best)->length : c->length < torso(best)->length))) best = k;
    }
    if (best < 0) throw InputError("avatar: no torso found between the crotch and the armpit");
    return best;
  };
  const int span = armpit - crotch;
  const int waist = extreme(crotch + static_cast<int>(0.35 * span), armpit - static_cast<int>(0.15 * span), false);
  const int hips = extreme(crotch + 1, waist, true);
  const int bust = extreme(waist, armpit - 1, true);
  L.waistHeight = levels[waist].y;
  L.waistCentre = torso(waist)->centroid;
  L.hipHeight = levels[hips].y;
  L.hipCentre = torso(hips)->centroid;
  L.bustHeight = levels[bust].y;
  L.bustCentre = torso(bust)->centroid;

  // Shoulders and arms.
  L.leftShoulder = shoulderPoint(mesh, neckPiece.bounds.max.x(), L.neckHeight, 1.0, H);
  L.rightShoulder = shoulderPoint(mesh, neckPiece.bounds.min.x(), L.neckHeight, -1.0, H);
  L.leftArm = armAxis(mesh, L.leftShoulder, 1.0, H, L.crotchHeight);
  L.rightArm = armAxis(mesh, L.rightShoulder, -1.0, H, L.crotchHeight);

  // Legs: the pieces on either side of the axis within the hips' width, from just below the crotch to the shins.
  const BoundingBox hipBox = torso(hips)->bounds;
  std::vector<Eigen::Vector3d> left, right;
  for (int k = crotch - levelAt(0.03); k > levelAt(0.12); --k) {
    const SliceComponent *l = nullptr, *r = nullptr;
    for (const SliceComponent& c : levels[k].pieces) {
      if (c.bounds.min.x() < hipBox.min.x() - 0.02 || c.bounds.max.x() > hipBox.max.x() + 0.02) continue;
      const SliceComponent*& side = c.centroid.x() > axisX ? l : r;
      if (!side || c.length > side->length) side = &c;
    }
    if (l) left.push_back(l->centroid);
    if (r) right.push_back(r->centroid);
  }
  if (left.size() < 4 || right.size() < 4) throw InputError("avatar: no legs found below the crotch");
  for (auto [axis, points] : {std::pair{&L.leftLeg, &left}, std::pair{&L.rightLeg, &right}}) {
    *axis = fitLine(*points);
    if (axis->direction.y() > 0) axis->direction = -axis->direction;
    slideOrigin(*axis, 1, L.crotchHeight);
  }
  return L;
}

}  // namespace drape
