#pragma once
// The contact part of a scene's solver: the merged collider (avatar + generated primitives) and the contact
// energies the scene needs (none without colliders; no friction term when friction is off or zero; no
// cloth-cloth term unless self-collision is on). Private to the engine.
#include <memory>
#include <vector>

#include "drape/collision/avatar_collider.h"
#include "drape/garment/garment.h"
#include "drape/newton/contact/avatar_contact.h"
#include "drape/newton/contact/avatar_feature_contact.h"
#include "drape/newton/contact/intersection_contour.h"
#include "drape/newton/energy.h"
#include "drape/scene/scene.h"
#include "drape/scene/stage_settings.h"

namespace drape {

struct ContactTerms {
  std::shared_ptr<const collision::AvatarCollider> collider;  // null when the scene has no collider
  double thickness = 0.0;                                     // metres
  std::vector<std::unique_ptr<newton::Energy>> energies;      // handed over to the solver
  // The avatar contact energy among them (owned by the solver once handed over), null without a collider.
  const newton::AvatarContactEnergy* avatarEnergy = nullptr;
  // The avatar feature contact among them, null unless contact.avatar_features found features.
  const newton::AvatarFeatureContactEnergy* featureEnergy = nullptr;
};

// settings: the scene's contact settings; scene: its fabrics (their stretch stiffness and friction coefficients);
// collider: the scene's merged collider (null when it has none), shared by the stages; pull: how the stage's solver
// takes the untangling pull (newton::ContourPull).
ContactTerms makeContactTerms(const ContactSettings& settings, const Scene& scene, const Garment& garment,
                              std::shared_ptr<const collision::AvatarCollider> collider, newton::ContourPull pull);

// |V| mask, 1 where the garment vertex (x flat, 3|V|) is within 1.5 contact thicknesses of a collider (a fresh
// query per vertex: for snapshots, not for every step).
Eigen::VectorXi contactMask(const ContactTerms& terms, const Eigen::VectorXd& x);
// Garment vertices closer than the contact thickness at x, from the avatar contact energy's own (cached)
// contact set; 0 without a collider.
int countContacts(const ContactTerms& terms, const Eigen::VectorXd& x);
// Avatar feature points closer than the contact thickness to the garment triangle they face at x (of the pairs
// held for the current step); 0 without the feature contact.
int countFeatureContacts(const ContactTerms& terms, const Eigen::VectorXd& x);

}  // namespace drape
