#include "sim/contact_terms.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "drape/newton/contact/avatar_feature_contact.h"
#include "drape/newton/contact/contact_factory.h"

namespace drape {

ContactTerms makeContactTerms(const ContactSettings& settings, const Scene& scene, const Garment& garment,
                              std::shared_ptr<const collision::AvatarCollider> collider, newton::ContourPull pull) {
  ContactTerms terms;
  terms.thickness = settings.thickness;
  terms.collider = std::move(collider);
  newton::ContactSetup setup;
  setup.avatar = terms.collider;
  setup.avatarContact.stiffness = settings.stiffness;
  setup.avatarContact.thickness = terms.thickness;
  double stretch = std::max(scene.fabric.stretchWarp, scene.fabric.stretchWeft);
  for (const auto& [panel, fabric] : scene.panelFabrics)
    stretch = std::max({stretch, fabric.stretchWarp, fabric.stretchWeft});
  setup.avatarContact.insideStiffnessFactor = newton::insideStiffnessFactorFor(setup.avatarContact, stretch);
  if (setup.avatar && settings.avatarFeatures && garment.triangles.rows() > 0) {
    // A triangle deeper behind a feature than half an edge is not one the body poked through.
    const double edge = collision::meanEdgeLength(garment.triangles, garment.positions);
    setup.featureRadius = collision::featureRadiusFor(edge, terms.thickness);
    setup.featureReach = 0.5 * edge;
  }
  setup.selfCollision = settings.selfCollision;
  setup.selfContact = setup.avatarContact;
  setup.contourPull = pull;
  // Friction only where there is something to rub against and a non-zero coefficient.
  if (settings.friction && (setup.avatar || setup.selfCollision)) {
    double mu = scene.fabric.friction;
    for (const auto& [panel, fabric] : scene.panelFabrics) mu = std::max(mu, fabric.friction);
    setup.frictionCoefficient = mu;
    setup.frictionMajorizer = settings.frictionMajorizer;
  }
  // Non-conforming seams: their edge stitches are excluded from cloth-cloth contact like the vertex pairs.
  std::vector<model::EdgeStitch> edgeStitches;
  edgeStitches.reserve(garment.edgeStitches.size());
  for (const GarmentEdgeStitch& e : garment.edgeStitches) edgeStitches.push_back({e.vertex, e.a, e.b, e.t});
  terms.energies =
      newton::makeContactEnergies(setup, garment.vertexCount(), garment.triangles, garment.stitchPairs, edgeStitches);
  for (const auto& energy : terms.energies) {
    if (const auto* avatar = dynamic_cast<const newton::AvatarContactEnergy*>(energy.get()))
      terms.avatarEnergy = avatar;
    if (const auto* features = dynamic_cast<const newton::AvatarFeatureContactEnergy*>(energy.get()))
      terms.featureEnergy = features;
  }
  return terms;
}

Eigen::VectorXi contactMask(const ContactTerms& terms, const Eigen::VectorXd& x) {
  const int n = static_cast<int>(x.size() / 3);
  Eigen::VectorXi mask = Eigen::VectorXi::Zero(n);
  if (!terms.collider) return mask;
  tbb::parallel_for(0, n, [&](int v) {
    collision::SurfacePoint sp;
    if (terms.collider->closest(x.segment<3>(3 * v), sp, 1.5 * terms.thickness) &&
        sp.signedDistance < 1.5 * terms.thickness)
      mask[v] = 1;
  });
  return mask;
}

int countContacts(const ContactTerms& terms, const Eigen::VectorXd& x) {
  return terms.avatarEnergy ? static_cast<int>(terms.avatarEnergy->contacts(x).size()) : 0;
}

int countFeatureContacts(const ContactTerms& terms, const Eigen::VectorXd& x) {
  return terms.featureEnergy ? static_cast<int>(terms.featureEnergy->contacts(x).size()) : 0;
}

}  // namespace drape
