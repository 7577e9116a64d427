#pragma once
// The mannequin as an implicit function: negative inside, roughly the signed distance in metres near the
// surface. The torso (with the neck) and each leg are stacks of analytic horizontal sections (superellipses
// with separate front and back half-depths, plus bust, seat and shoulder-blade lobes) whose parameters are
// functions of the measurements at the landmark levels, interpolated by monotone cubics in between; the torso
// sections at the bust, underbust, waist and hip levels and the legs at the crotch are scaled so that their
// convex-hull girths equal the measurements. The head is an ellipsoid, the feet rounded ellipsoids and the arms
// tapered tubes at the arm pose angle; the parts are joined by a polynomial smooth minimum, and the torso
// narrows into the thighs above the crotch.
// docs/MANNEQUIN.md states every proportion constant.
#include <Eigen/Core>
#include <vector>

#include "drape/avatar/body_measurements.h"
#include "drape/avatar/mannequin.h"
#include "drape/geometry/triangle_mesh.h"

namespace drape::mannequin_detail {

// A monotone cubic (Fritsch-Carlson) through (x[i], y[i]), constant outside; x strictly increasing.
struct Profile {
  std::vector<double> x;
  std::vector<double> y;
  double operator()(double t) const;
};

// One horizontal torso section, metres, in the x-z plane about the centre (0, cz): a superellipse
// |x / halfWidth|^exponent + |dz / depth|^exponent = 1 with depth = front for dz > 0 (the body faces +z) and
// back for dz < 0, plus Gaussian lobes added along the ray: bust (front, at x = +-0.55 halfWidth), seat
// (back, x = +-0.45 halfWidth) and shoulder blades (back, x = +-0.5 halfWidth).
struct TorsoSection {
  double halfWidth = 0.0;
  double front = 0.0;
  double back = 0.0;
  double cz = 0.0;
  double exponent = 2.0;
  double bust = 0.0;
  double seat = 0.0;
  double blades = 0.0;

  // Distance (metres) from the centre to the outline in direction theta (from +x towards +z).
  double radius(double theta) const;
  // Convex-hull perimeter (metres) of the outline.
  double girth() const;
  // The same shape scaled horizontally about its centre by s.
  TorsoSection scaled(double s) const;
};

// Landmark heights (metres) for these measurements; InputError when they are out of order.
MannequinLevels levelsFor(const BodyMeasurements& measurements);

class MannequinShape {
 public:
  explicit MannequinShape(const BodyMeasurements& measurements);

  // p: metres. < 0 inside.
  double value(const Eigen::Vector3d& p) const;

  const MannequinLevels& levels() const { return m_levels; }
  // A box that contains the whole body, and a point well inside it.
  const BoundingBox& bounds() const { return m_bounds; }
  Eigen::Vector3d interiorPoint() const;
  // The torso section at height y (metres), before it narrows into the thighs and is cut above the neck.
  TorsoSection torsoSection(double y) const;

 private:
  struct LegSection {  // ellipse centred at (cx, cz) with half-axes rx (x) and rz (z)
    double cx, cz, rx, rz;
  };

  double torso(const Eigen::Vector3d& p) const;
  double leg(const Eigen::Vector3d& p) const;  // the +x leg with its foot; mirror p for the other one
  double arm(const Eigen::Vector3d& p) const;  // the +x arm; mirror p for the other one
  double head(const Eigen::Vector3d& p) const;

  MannequinLevels m_levels;
  // Torso parameters over height, one profile per TorsoSection field.
  Profile m_halfWidth, m_front, m_back, m_cz, m_exponent, m_bust, m_seat, m_blades;
  Profile m_legCx, m_legCz, m_legRx, m_legRz;  // leg ellipse over height
  double m_crotchJoin = 0.0;  // the height where the torso meets the thighs' surface (kCrotchFlare)
  double m_neckTop = 0.0;
  double m_legTop = 0.0;  // above it the thighs lie inside the torso (kThighTaper)
  Eigen::Vector3d m_headCentre, m_headRadii;
  Eigen::Vector3d m_footCentre, m_footRadii;  // the +x foot
  // The +x arm: one tube along m_armDir from m_armJoint, its radius a profile over the distance along the axis
  // (to m_armLength, the fingertips), so that it tapers without the rings of a chain of blended cones.
  Eigen::Vector3d m_armJoint, m_armDir;
  double m_armLength = 0.0;
  Profile m_armRadius;
  Eigen::Vector3d m_deltoidCentre;
  Eigen::Vector3d m_deltoidRadii;
  BoundingBox m_bounds;
};

}  // namespace drape::mannequin_detail
