// Composition of the contact terms; see contact_factory.h.
#include "drape/newton/contact/contact_factory.h"

#include "drape/newton/contact/avatar_feature_contact.h"
#include "drape/newton/contact/intersection_contour.h"
#include "drape/newton/contact/self_contact.h"

namespace drape::newton {

std::vector<std::unique_ptr<Energy>> makeContactEnergies(const ContactSetup& setup, int vertexCount,
                                                         const Eigen::MatrixX3i& triangles,
                                                         const std::vector<std::pair<int, int>>& stitches,
                                                         const std::vector<model::EdgeStitch>& edgeStitches) {
  std::vector<std::unique_ptr<Energy>> out;
  const AvatarContactEnergy* avatar = nullptr;
  const SelfContactEnergy* self = nullptr;
  const AvatarFeatureContactEnergy* featureContact = nullptr;
  if (setup.avatar) {
    auto e = std::make_unique<AvatarContactEnergy>(setup.avatar, vertexCount, setup.avatarContact);
    avatar = e.get();
    out.push_back(std::move(e));
    if (setup.featureRadius > 0.0 && triangles.rows() > 0) {
      std::vector<collision::FeatureVertex> features =
          collision::avatarFeatureVertices(setup.avatar->mesh(), setup.featureRadius);
      if (!features.empty()) {
        auto f = std::make_unique<AvatarFeatureContactEnergy>(std::move(features), triangles, setup.avatarContact,
                                                              setup.featureReach);
        featureContact = f.get();
        out.push_back(std::move(f));
      }
    }
  }
  if (setup.selfCollision && triangles.rows() > 0) {
    auto e = std::make_unique<SelfContactEnergy>(triangles, vertexCount,
                                                 collision::contactMergedVertices(stitches, edgeStitches),
                                                 setup.selfContact, setup.selfMargin);
    self = e.get();
    out.push_back(std::move(e));
    // Pulled as hard as the contact pushes at its full thickness.
    out.push_back(std::make_unique<IntersectionContourEnergy>(
        self, setup.selfContact.stiffness * setup.selfContact.thickness, setup.contourPull));
  }
  if (setup.frictionCoefficient > 0.0 && (avatar || self)) {
    const FrictionParameters friction{setup.frictionCoefficient, setup.frictionEpsV, setup.frictionMajorizer};
    out.push_back(std::make_unique<FrictionEnergy>(avatar, self, friction, featureContact));
  }
  return out;
}

}  // namespace drape::newton
