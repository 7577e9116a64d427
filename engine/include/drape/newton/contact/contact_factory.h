#pragma once
// Builds only the contact terms a scene needs (DESIGN.md section 1): no avatar -> no avatar contact and no
// collider; self-collision off -> no cloth-cloth BVH; friction coefficient 0 -> no friction energy; an avatar
// without features sharper than featureRadius -> no feature contact. The energies come back in the order the
// solver should call beginStep in, named "avatar_contact", "avatar_feature_contact", "self_contact",
// "intersection_contour" (with self contact: it pulls crossings free, intersection_contour.h), "friction".
#include <Eigen/Core>
#include <memory>
#include <utility>
#include <vector>

#include "drape/collision/avatar_collider.h"
#include "drape/model/cloth_model.h"
#include "drape/newton/contact/avatar_contact.h"
#include "drape/newton/contact/friction.h"
#include "drape/newton/contact/intersection_contour.h"
#include "drape/newton/energy.h"

namespace drape::newton {

struct ContactSetup {
  std::shared_ptr<const collision::AvatarCollider> avatar;  // null: the scene has no avatar
  ContactParameters avatarContact;
  // Avatar vertices whose radius of curvature is below this (metres) also push the garment's triangles
  // (avatar_feature_contact.h, "avatar_feature_contact"); 0: none.
  double featureRadius = 0.0;
  double featureReach = 0.01;  // metres behind a feature within which a garment triangle is still pushed out
  bool selfCollision = false;
  ContactParameters selfContact;
  double selfMargin = 0.0;           // extra BVH search radius beyond the thickness, metres (0: = thickness)
  ContourPull contourPull = ContourPull::Followed;  // how the untangling pull enters a step (the solver's choice)
  double frictionCoefficient = 0.0;  // mu; 0 creates no friction energy
  double frictionEpsV = 1e-3;        // m/s, see FrictionParameters
  bool frictionMajorizer = true;     // see FrictionParameters::majorizeAtPrediction
};

// Garment: vertexCount vertices, triangles |F| x 3, stitched vertex pairs and edge stitches (non-conforming
// seams); neither repels across its seam (collision/contact_merged_vertices.h).
// The friction energy, when created, points at the contact energies in the same list: keep the list together.
std::vector<std::unique_ptr<Energy>> makeContactEnergies(const ContactSetup& setup, int vertexCount,
                                                         const Eigen::MatrixX3i& triangles,
                                                         const std::vector<std::pair<int, int>>& stitches,
                                                         const std::vector<model::EdgeStitch>& edgeStitches = {});

}  // namespace drape::newton
