#include "sim/contact_terms.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "drape/collision/contact_factory.h"
#include "sim/cloth_model_builder.h"

namespace drape {
namespace {

// Metres: the bluntest avatar feature that pushes garment triangles (a bust point, a shoulder tip, an elbow).
constexpr double kMaxFeatureRadius = 0.03;

}  // namespace

ContactTerms makeContactTerms(const Scene& scene, const Garment& garment,
                              std::shared_ptr<const collision::AvatarCollider> collider) {
  ContactTerms terms;
  terms.thickness = contactThickness(scene);
  terms.collider = std::move(collider);
  collision::ContactSetup setup;
  setup.avatar = terms.collider;
  setup.avatarContact.stiffness = scene.settings.number("contact.stiffness");
  setup.avatarContact.thickness = terms.thickness;
  if (setup.avatar && scene.settings.flag("contact.avatar_features") && garment.triangles.rows() > 0) {
    // Over a cap of radius R a triangle of mean edge L sags about L^2 / (8 R) below its vertices, which the vertex
    // contact keeps 0 to t (the thickness) off the body: features whose sag reaches t / 2 (R < L^2 / (4 t)) are
    // watched, up to kMaxFeatureRadius: on a coarse mesh the criterion takes in the whole body (a 4 cm mesh: radii
    // up to 20 cm), and blunt features holding every triangle slow the drape down without showing any better.
    // A triangle deeper behind a feature than half an edge is not one the body poked through.
    const auto& x = garment.positions;
    const auto& f = garment.triangles;
    double length = 0.0;
    for (int t = 0; t < f.rows(); ++t)
      for (int k = 0; k < 3; ++k) length += (x.row(f(t, k)) - x.row(f(t, (k + 1) % 3))).norm();
    length /= 3.0 * static_cast<double>(f.rows());
    setup.featureRadius = std::min(length * length / (4.0 * terms.thickness), kMaxFeatureRadius);
    setup.featureReach = 0.5 * length;
  }
  setup.selfCollision = scene.settings.flag("contact.self_collision");
  setup.selfContact = setup.avatarContact;
  // Friction only where there is something to rub against and a non-zero coefficient.
  if (scene.settings.flag("contact.friction") && (setup.avatar || setup.selfCollision)) {
    double mu = scene.fabric.friction;
    for (const auto& [panel, fabric] : scene.panelFabrics) mu = std::max(mu, fabric.friction);
    setup.frictionCoefficient = mu;
  }
  // Non-conforming seams: their edge stitches are excluded from cloth-cloth contact like the vertex pairs.
  std::vector<newton::EdgeStitch> edgeStitches;
  edgeStitches.reserve(garment.edgeStitches.size());
  for (const GarmentEdgeStitch& e : garment.edgeStitches) edgeStitches.push_back({e.vertex, e.a, e.b, e.t});
  terms.energies = collision::makeContactEnergies(setup, garment.vertexCount(), garment.triangles, garment.stitchPairs,
                                                  edgeStitches);
  for (const auto& energy : terms.energies)
    if (const auto* avatar = dynamic_cast<const collision::AvatarContactEnergy*>(energy.get()))
      terms.avatarEnergy = avatar;
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

}  // namespace drape
