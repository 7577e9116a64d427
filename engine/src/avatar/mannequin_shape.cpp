#include "avatar/mannequin_shape.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "drape/core/input_error.h"

namespace drape::mannequin_detail {
namespace {

constexpr double kPi = std::numbers::pi;

// Default vertical landmarks as fractions of the height (docs/MANNEQUIN.md, "Proportion constants").
constexpr double kHeadLengthOfHeight = 0.150;
constexpr double kWaistLineOfHeight = 0.220;
constexpr double kHipsLineOfHeight = 0.130;
constexpr double kCrotchHipOfHeight = 0.050;
constexpr double kVertBustLineOfHeight = 0.125;
// The underbust lies this fraction of the way from the bust level down to the waist level.
constexpr double kUnderbustFraction = 0.45;
// Other levels: armpit as a fraction of the way from the bust up to the neck base; knee, calf, lower calf and
// ankle as fractions of the height.
constexpr double kArmpitFraction = 0.22;
constexpr double kKneeOfHeight = 0.275;
constexpr double kCalfOfHeight = 0.205;
constexpr double kLowerCalfOfHeight = 0.12;
constexpr double kAnkleOfHeight = 0.045;
// Stance: the ankles' centres lie this far (metres) outside and behind the thighs' centres at the crotch.
constexpr double kStance = 0.01;
constexpr double kLegLean = 0.055;

// Smooth-minimum radii (metres): legs to torso, arm parts to each other, arms to torso, head to neck, foot.
constexpr double kLegBlend = 0.012;
// Where the torso meets the thighs: the torso may reach kCrotchFlare metres beyond the thighs per metre above the
// crotch join, and the thighs beyond the torso kThighTaper metres per metre below the legs' top, so that each
// narrows into the other along a slope instead of ending in a ledge. The join lies so that the torso bridges the gap
// between the thighs kCrotchBridge above the crotch level, where the thighs are still apart and leg_circ is
// measured. kHipBlend rounds those slopes.
constexpr double kCrotchFlare = 1.0;
constexpr double kThighTaper = 0.4;
constexpr double kCrotchBridge = 0.015;
constexpr double kHipBlend = 0.02;
constexpr double kArmPartBlend = 0.015;
constexpr double kArmBlend = 0.02;
constexpr double kHeadBlend = 0.03;
constexpr double kFootBlend = 0.03;

// Polynomial smooth minimum (Quilez): equal to min(a, b) where |a - b| >= k.
double smoothMin(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - h * h * k * 0.25;
}

double smoothMax(double a, double b, double k) { return -smoothMin(-a, -b, k); }

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Perimeter of the convex hull of points (Andrew's monotone chain).
double hullPerimeter(std::vector<Eigen::Vector2d> p) {
  std::sort(p.begin(), p.end(),
            [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  std::vector<Eigen::Vector2d> hull(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  double perimeter = 0.0;
  for (size_t i = 0; i + 1 < k; ++i) perimeter += (hull[i + 1] - hull[i]).norm();
  return perimeter;
}

// Perimeter of an ellipse with half-axes a, b (Ramanujan's second approximation, relative error < 1e-9 for
// the aspect ratios used here).
double ellipsePerimeter(double a, double b) {
  const double h = (a - b) * (a - b) / ((a + b) * (a + b));
  return kPi * (a + b) * (1.0 + 3.0 * h / (10.0 + std::sqrt(4.0 - 3.0 * h)));
}

double ellipsoid(const Eigen::Vector3d& p, const Eigen::Vector3d& centre, const Eigen::Vector3d& radii) {
  return ((p - centre).cwiseQuotient(radii).norm() - 1.0) * radii.minCoeff();
}

double lobe(double x, double centre, double width) {
  const double t = (std::abs(x) - centre) / width;
  return std::exp(-t * t);
}

}  // namespace

double Profile::operator()(double t) const {
  const size_t n = x.size();
  if (t <= x.front()) return y.front();
  if (t >= x.back()) return y.back();
  const size_t i = static_cast<size_t>(std::upper_bound(x.begin(), x.end(), t) - x.begin()) - 1;
  // Fritsch-Carlson tangents: harmonic-type mean of the neighbouring secants, zero at extrema.
  auto secant = [&](size_t k) { return (y[k + 1] - y[k]) / (x[k + 1] - x[k]); };
  auto tangent = [&](size_t k) {
    if (k == 0) return secant(0);
    if (k == n - 1) return secant(n - 2);
    const double s0 = secant(k - 1), s1 = secant(k);
    if (s0 * s1 <= 0.0) return 0.0;
    const double h0 = x[k] - x[k - 1], h1 = x[k + 1] - x[k];
    const double w0 = 2.0 * h1 + h0, w1 = h1 + 2.0 * h0;
    return (w0 + w1) / (w0 / s0 + w1 / s1);
  };
  const double h = x[i + 1] - x[i];
  const double u = (t - x[i]) / h;
  const double h00 = 2 * u * u * u - 3 * u * u + 1, h10 = u * u * u - 2 * u * u + u;
  const double h01 = -2 * u * u * u + 3 * u * u, h11 = u * u * u - u * u;
  return h00 * y[i] + h10 * h * tangent(i) + h01 * y[i + 1] + h11 * h * tangent(i + 1);
}

double TorsoSection::radius(double theta) const {
  const double c = std::cos(theta), s = std::sin(theta);
  const double depth = s > 0.0 ? front : back;
  const double r0 =
      std::pow(std::pow(std::abs(c) / halfWidth, exponent) + std::pow(std::abs(s) / depth, exponent), -1.0 / exponent);
  const double x0 = r0 * c;
  double r = r0;
  if (s > 0.0) {
    r += bust * s * lobe(x0, 0.55 * halfWidth, 0.28 * halfWidth);
  } else {
    r += -s * (seat * lobe(x0, 0.45 * halfWidth, 0.35 * halfWidth) +
               blades * lobe(x0, 0.5 * halfWidth, 0.3 * halfWidth));
  }
  return r;
}

double TorsoSection::girth() const {
  constexpr int kSamples = 720;
  std::vector<Eigen::Vector2d> points;
  points.reserve(kSamples);
  for (int k = 0; k < kSamples; ++k) {
    const double theta = 2.0 * kPi * k / kSamples;
    const double r = radius(theta);
    points.emplace_back(r * std::cos(theta), r * std::sin(theta));
  }
  return hullPerimeter(std::move(points));
}

TorsoSection TorsoSection::scaled(double s) const {
  TorsoSection t = *this;
  t.halfWidth *= s;
  t.front *= s;
  t.back *= s;
  t.bust *= s;
  t.seat *= s;
  t.blades *= s;
  return t;
}

MannequinLevels levelsFor(const BodyMeasurements& m) {
  const double h = m.height;
  MannequinLevels l;
  l.top = h;
  l.neckBase = h - m.headLength.value_or(kHeadLengthOfHeight * h);
  l.waist = l.neckBase - m.waistLine.value_or(kWaistLineOfHeight * h);
  l.hips = l.waist - m.hipsLine.value_or(kHipsLineOfHeight * h);
  l.crotch = l.hips - m.crotchHipDiff.value_or(kCrotchHipOfHeight * h);
  l.bust = l.neckBase - m.vertBustLine.value_or(kVertBustLineOfHeight * h);
  l.underbust = l.bust - kUnderbustFraction * (l.bust - l.waist);
  const double order[] = {kKneeOfHeight * h + 0.05, l.crotch, l.hips, l.waist, l.underbust, l.bust, l.neckBase, l.top};
  const char* names[] = {"knee (27.5% of the height) + 5 cm", "crotch", "hips", "waist", "underbust", "bust",
                         "neck base", "top"};
  for (int i = 0; i + 1 < 8; ++i) {
    if (!(order[i] < order[i + 1])) {
      std::ostringstream s;
      s << "body measurements: the " << names[i + 1] << " level (" << order[i + 1] << " m, from height, head_l, "
        << "waist_line, hips_line, crotch_hip_diff and vert_bust_line) is not above the " << names[i] << " level ("
        << order[i] << " m)";
      throw InputError(s.str());
    }
  }
  return l;
}

MannequinShape::MannequinShape(const BodyMeasurements& m) : m_levels(levelsFor(m)) {
  const MannequinLevels& l = m_levels;
  const double height = m.height;
  const double headLength = l.top - l.neckBase;

  // ---- Legs: ellipses, the thigh fitted exactly at the crotch; other girths in proportion to the thigh. ----
  struct LegLevel {
    double y, girth, depthRatio, cx, cz;
  };
  const double thighRatio = 1.0;
  const double thighRx = m.thigh / ellipsePerimeter(1.0, thighRatio);
  const double thighGap = 0.016;  // between the inner thighs at the crotch
  const double crotchCx = thighRx + 0.5 * thighGap;
  const double knee = kKneeOfHeight * height;
  const double ankle = kAnkleOfHeight * height;
  // The leg axis runs from the crotch out by kStance and back by kLegLean at the ankle (linear in height).
  auto axisX = [&](double y) { return crotchCx + kStance * (l.crotch - y) / (l.crotch - ankle); };
  auto axisZ = [&](double y) { return -kLegLean * (l.crotch - y) / (l.crotch - ankle); };
  const double midThigh = l.crotch - 0.45 * (l.crotch - knee);
  const double calf = kCalfOfHeight * height, lowerCalf = kLowerCalfOfHeight * height;
  const std::vector<LegLevel> legLevels = {
      {ankle, 1.35 * m.wrist, 0.85, axisX(ankle), axisZ(ankle)},
      {lowerCalf, 0.42 * m.thigh, 0.95, axisX(lowerCalf), axisZ(lowerCalf) - 0.008},
      {calf, 0.62 * m.thigh, 0.95, axisX(calf), axisZ(calf) - 0.012},
      {knee, 0.63 * m.thigh, 0.95, axisX(knee), axisZ(knee)},
      {midThigh, 0.85 * m.thigh, 1.0, axisX(midThigh), axisZ(midThigh)},
      {l.crotch, m.thigh, thighRatio, crotchCx, 0.0},
  };
  for (const LegLevel& level : legLevels) {
    const double rx = level.girth / ellipsePerimeter(1.0, level.depthRatio);
    m_legCx.x.push_back(level.y);
    m_legCx.y.push_back(level.cx);
    m_legCz.x.push_back(level.y);
    m_legCz.y.push_back(level.cz);
    m_legRx.x.push_back(level.y);
    m_legRx.y.push_back(rx);
    m_legRz.x.push_back(level.y);
    m_legRz.y.push_back(rx * level.depthRatio);
  }
  m_legTop = l.crotch + 0.5 * (l.hips - l.crotch);
  m_crotchJoin = l.crotch + kCrotchBridge - 0.5 * thighGap / kCrotchFlare;
  const double footScale = height / 1.70;
  m_footCentre = Eigen::Vector3d(axisX(ankle) + 0.01, 0.03 * footScale, axisZ(ankle) + 0.085 * footScale);
  m_footRadii = Eigen::Vector3d(0.05, 0.045, 0.128) * footScale;

  // ---- Torso: superellipse sections at the landmark levels. ----
  // Lobe sizes from the measurements: bust from the bust-underbust difference, seat from hips - waist.
  const double bustLobe = std::clamp(0.5 * (m.bust - m.underbust - 0.04), 0.0, 0.08);
  const double seatLobe = std::clamp(0.2 * (m.hips - m.waist), 0.01, 0.05);
  const double bladeLobe = 0.008;
  // A section with the given proportions, scaled so that its convex-hull girth is `girth`.
  auto fitted = [](double girth, double frontRatio, double backRatio, double exponent, double cz, double bust,
                   double seat, double blades) {
    TorsoSection s;
    s.halfWidth = 0.17 * girth;
    s.front = frontRatio * s.halfWidth;
    s.back = backRatio * s.halfWidth;
    s.exponent = exponent;
    s.cz = cz;
    s.bust = bust;
    s.seat = seat;
    s.blades = blades;
    return s.scaled(girth / s.girth());
  };
  const TorsoSection hips = fitted(m.hips, 0.58, 0.55, 2.3, -0.012, 0.0, seatLobe, 0.0);
  const TorsoSection waist = fitted(m.waist, 0.72, 0.62, 2.2, 0.012, 0.0, 0.15 * seatLobe, 0.0);
  const TorsoSection underbust = fitted(m.underbust, 0.70, 0.70, 2.3, 0.005, 0.0, 0.0, 0.5 * bladeLobe);
  const TorsoSection bust = fitted(m.bust, 0.62, 0.70, 2.4, 0.0, bustLobe, 0.0, bladeLobe);

  TorsoSection crotch = hips;  // the hull of the thighs, inside the legs' blend
  crotch.halfWidth = crotchCx + thighRx;
  crotch.front = 0.55 * crotch.halfWidth;
  crotch.back = 0.5 * crotch.halfWidth;
  crotch.seat = 0.6 * seatLobe;
  crotch.exponent = 2.2;

  TorsoSection armpit = bust;
  armpit.front = 0.9 * bust.front;
  armpit.bust = 0.3 * bust.bust;
  armpit.exponent = 2.5;
  armpit.cz = -0.008;

  const double neckScale = m.neckWidth / 0.19;
  TorsoSection shoulder;
  shoulder.halfWidth = 0.5 * m.shoulderWidth - 0.015;
  shoulder.front = 0.065 * neckScale;
  shoulder.back = 0.075 * neckScale;
  shoulder.exponent = 1.8;
  shoulder.cz = -0.02;
  shoulder.blades = 0.5 * bladeLobe;

  TorsoSection neckBase;
  neckBase.halfWidth = 0.5 * m.neckWidth;
  neckBase.front = 0.045 * neckScale;
  neckBase.back = 0.055 * neckScale;
  neckBase.exponent = 2.0;
  neckBase.cz = -0.03;

  TorsoSection neck;
  neck.halfWidth = 0.31 * m.neckWidth;
  neck.front = neck.back = 1.05 * neck.halfWidth;
  neck.exponent = 2.0;
  neck.cz = -0.02;
  TorsoSection neckTop = neck;
  neckTop.cz = -0.01;

  // The acromion level from the shoulder slope (about 20 degrees from the side neck point).
  const double shoulderLevel = l.neckBase - 0.5 * (m.shoulderWidth - m.neckWidth) * std::tan(20.0 * kPi / 180.0);
  const double armpitLevel = l.bust + kArmpitFraction * (l.neckBase - l.bust);
  m_neckTop = l.top - 0.35 * headLength;
  const std::vector<std::pair<double, TorsoSection>> torsoLevels = {
      {l.crotch, crotch},
      {l.hips, hips},
      {l.waist, waist},
      {l.underbust, underbust},
      {l.bust, bust},
      {armpitLevel, armpit},
      {std::max(shoulderLevel, armpitLevel + 0.02), shoulder},
      {l.neckBase, neckBase},
      {l.neckBase + 0.2 * headLength, neck},
      {m_neckTop, neckTop},
  };
  for (const auto& [y, s] : torsoLevels) {
    for (Profile* p : {&m_halfWidth, &m_front, &m_back, &m_cz, &m_exponent, &m_bust, &m_seat, &m_blades})
      p->x.push_back(y);
    m_halfWidth.y.push_back(s.halfWidth);
    m_front.y.push_back(s.front);
    m_back.y.push_back(s.back);
    m_cz.y.push_back(s.cz);
    m_exponent.y.push_back(s.exponent);
    m_bust.y.push_back(s.bust);
    m_seat.y.push_back(s.seat);
    m_blades.y.push_back(s.blades);
  }
  for (size_t i = 0; i + 1 < m_halfWidth.x.size(); ++i) {
    if (!(m_halfWidth.x[i] < m_halfWidth.x[i + 1])) {
      std::ostringstream s;
      s << "body measurements: the torso levels are not in order at " << m_halfWidth.x[i + 1]
        << " m (check head_l, vert_bust_line, shoulder_w and neck_w)";
      throw InputError(s.str());
    }
  }

  // ---- Head: an ellipsoid whose top is at the height. ----
  m_headRadii = Eigen::Vector3d(0.30, 0.43, 0.38) * headLength;
  m_headCentre = Eigen::Vector3d(0.0, l.top - m_headRadii.y(), 0.025);

  // ---- Arms: a tapered tube from the shoulder joint along the pose direction; arm_length is shoulder to wrist. ----
  const double angle = m.armPoseAngle * kPi / 180.0;
  const Eigen::Vector3d dir(std::cos(angle), -std::sin(angle), 0.0);
  const Eigen::Vector3d joint(0.5 * m.shoulderWidth - 0.012, l.neckBase - 0.05 * height, -0.01 * m.bust);
  const double wristRadius = m.wrist / (2.0 * kPi);
  const double handLength = 0.1 * height;
  const double length = m.armLength;
  // Radius over the distance along the axis: shoulder, upper arm, elbow, forearm, wrist, fingertips.
  m_armJoint = joint;
  m_armDir = dir;
  m_armLength = length + handLength;
  const std::vector<std::pair<double, double>> armRadii = {
      {0.0, 0.050 * m.bust},           {0.25 * length, 0.046 * m.bust}, {0.47 * length, 1.45 * wristRadius},
      {0.75 * length, 1.3 * wristRadius}, {length, wristRadius},          {m_armLength, 0.013 * height}};
  for (const auto& [s, r] : armRadii) {
    m_armRadius.x.push_back(s);
    m_armRadius.y.push_back(r);
  }
  m_deltoidCentre = joint + Eigen::Vector3d(0.008, 0.0, 0.0);
  m_deltoidRadii = Eigen::Vector3d(0.055, 0.058, 0.068) * m.bust;

  // Bounds: the widest torso section, the legs, the feet, the head and the arms' cones.
  double half = 0.0;
  for (const auto& [y, s] : torsoLevels)
    half = std::max({half, s.halfWidth, std::abs(s.cz) + s.front + s.bust, std::abs(s.cz) + s.back + s.seat});
  for (double cx : m_legCx.y) half = std::max(half, cx + 1.2 * m.thigh / (2.0 * kPi));
  half = std::max(half, m_footCentre.z() + m_footRadii.z());
  half += 0.05;
  m_bounds.extend(Eigen::Vector3d(-half, 0.0, -half));
  m_bounds.extend(Eigen::Vector3d(half, height, half));
  const double armRadius = *std::max_element(m_armRadius.y.begin(), m_armRadius.y.end());
  for (const Eigen::Vector3d& q : {m_armJoint, Eigen::Vector3d(m_armJoint + m_armLength * m_armDir)}) {
    m_bounds.extend(Eigen::Vector3d(q + Eigen::Vector3d::Constant(armRadius)));
    m_bounds.extend(Eigen::Vector3d(-q.x() - armRadius, q.y() - armRadius, q.z() - armRadius));
  }
}

TorsoSection MannequinShape::torsoSection(double y) const {
  TorsoSection s;
  s.halfWidth = m_halfWidth(y);
  s.front = m_front(y);
  s.back = m_back(y);
  s.cz = m_cz(y);
  s.exponent = m_exponent(y);
  s.bust = m_bust(y);
  s.seat = m_seat(y);
  s.blades = m_blades(y);
  return s;
}

Eigen::Vector3d MannequinShape::interiorPoint() const {
  return Eigen::Vector3d(0.0, m_levels.hips, m_cz(m_levels.hips));
}

double MannequinShape::torso(const Eigen::Vector3d& p) const {
  const TorsoSection s = torsoSection(p.y());
  const double dx = p.x(), dz = p.z() - s.cz;
  const double d = std::hypot(dx, dz) - s.radius(std::atan2(dz, dx));
  return std::max(d, p.y() - m_neckTop);
}

double MannequinShape::leg(const Eigen::Vector3d& p) const {
  const double y = p.y();
  const double rx = m_legRx(y), rz = m_legRz(y);
  const double dx = p.x() - m_legCx(y), dz = p.z() - m_legCz(y);
  const double rho = std::hypot(dx, dz);
  double d = rho;
  if (rho > 0.0) {
    const double c = dx / rho, s = dz / rho;
    d = rho - 1.0 / std::sqrt(c * c / (rx * rx) + s * s / (rz * rz));
  }
  return smoothMin(d, ellipsoid(p, m_footCentre, m_footRadii), kFootBlend);
}

double MannequinShape::arm(const Eigen::Vector3d& p) const {
  const double s = std::clamp((p - m_armJoint).dot(m_armDir), 0.0, m_armLength);
  const double tube = (p - (m_armJoint + s * m_armDir)).norm() - m_armRadius(s);
  return smoothMin(ellipsoid(p, m_deltoidCentre, m_deltoidRadii), tube, kArmPartBlend);
}

double MannequinShape::head(const Eigen::Vector3d& p) const { return ellipsoid(p, m_headCentre, m_headRadii); }

double MannequinShape::value(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d mirrored(-p.x(), p.y(), p.z());
  const Eigen::Vector3d& right = p.x() >= 0.0 ? p : mirrored;  // legs and arms are mirror images
  const Eigen::Vector3d& left = p.x() >= 0.0 ? mirrored : p;
  const double legs = std::min(leg(right), leg(left)), body = torso(p);
  const double torsoAboveThighs = smoothMax(body, legs - kCrotchFlare * (p.y() - m_crotchJoin), kHipBlend);
  const double thighsBelowTorso = smoothMax(legs, body - kThighTaper * (m_legTop - p.y()), kHipBlend);
  double d = smoothMin(torsoAboveThighs, head(p), kHeadBlend);
  d = smoothMin(d, thighsBelowTorso, kLegBlend);
  d = smoothMin(d, std::min(arm(right), arm(left)), kArmBlend);
  // Flat soles and nothing above the top of the head.
  return std::max({d, -p.y(), p.y() - m_levels.top});
}

}  // namespace drape::mannequin_detail
