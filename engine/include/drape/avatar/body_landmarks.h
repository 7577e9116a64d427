#pragma once
// Landmarks of a standing body mesh (metres, y up, facing +z, its left at +x), found from the mesh alone by
// slicing it: horizontal slices (y = const) give the neck, the armpit, the torso's girth levels and the crotch,
// vertical slices (x = const) the arms, in an A-pose as in a T-pose. Used to fit a pattern laid out around another
// body to the avatar it is draped on (garment/placement_fit.h).
#include <Eigen/Core>
#include <vector>

#include "drape/geometry/triangle_mesh.h"

namespace drape {

// One connected piece of a plane's cut through the mesh (a closed contour on a closed mesh).
struct SliceComponent {
  double length = 0.0;                                 // contour length, metres
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // length-weighted centroid of the contour
  BoundingBox bounds;
};

// The connected pieces of the cut of mesh by the plane {p : p[axis] = value} (axis 0 = x, 1 = y, 2 = z), longest
// first. Pieces join where their segments share a mesh edge.
std::vector<SliceComponent> sliceMesh(const TriangleMesh& mesh, int axis, double value);

// A line through origin along a unit direction.
struct BodyAxis {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitY();
};

struct BodyLandmarks {
  double floor = 0.0;   // lowest y of the mesh
  double height = 0.0;  // top of the head above the floor
  Eigen::Vector3d headTop = Eigen::Vector3d::Zero();
  double neckHeight = 0.0;                               // y of the narrowest slice of the neck
  Eigen::Vector3d neckCentre = Eigen::Vector3d::Zero();  // its centroid
  // Shoulder points (acromion): where the top outline of the shoulder turns down into the arm, seen from the
  // front; y is the top of the body there. Left = +x.
  Eigen::Vector3d leftShoulder = Eigen::Vector3d::Zero();
  Eigen::Vector3d rightShoulder = Eigen::Vector3d::Zero();
  // Arm axes: origin below the shoulder point, on the axis; direction from the shoulder towards the wrist.
  BodyAxis leftArm;
  BodyAxis rightArm;
  double armpitHeight = 0.0;  // highest horizontal slice below the neck where the torso is cut apart from the arms
  double bustHeight = 0.0;    // widest torso slice between the waist and the armpit
  double waistHeight = 0.0;   // narrowest torso slice between the hips and the bust
  double hipHeight = 0.0;     // widest torso slice between the crotch and the waist
  Eigen::Vector3d bustCentre = Eigen::Vector3d::Zero();
  Eigen::Vector3d waistCentre = Eigen::Vector3d::Zero();
  Eigen::Vector3d hipCentre = Eigen::Vector3d::Zero();
  double crotchHeight = 0.0;  // highest horizontal slice where the legs are apart
  BodyAxis leftLeg;           // from the crotch down, direction towards the ankle
  BodyAxis rightLeg;

  // The body's vertical axis at height y: the torso centre interpolated between the landmark centres (hips,
  // waist, bust, neck), held constant beyond them.
  Eigen::Vector3d centreAt(double y) const;
};

// Throws InputError ("avatar: ...") when the mesh does not look like a standing body (no neck, no separate arms
// or legs found).
BodyLandmarks findBodyLandmarks(const TriangleMesh& mesh);

}  // namespace drape
