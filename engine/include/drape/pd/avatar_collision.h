#pragma once
// Cloth-avatar contact constraints of the PD preview (pd-dd sections 6, 7.3): one position constraint (A_k = I)
// per garment vertex that is within the contact thickness of the collider, or whose path over the step crossed
// the collider surface, with a lagged Coulomb friction correction of the target. Two ways to find the target:
//   StepPlanes: each watched DOF gets, once per step, the half-space {y : (y - p) . n >= thickness}
//     of the tangent plane at the closest surface point p (outward pseudo-normal n) of its position at the step
//     start, so the side a vertex came from decides (no tunnelling). In every L-G iteration the collision-free
//     position x is projected onto the DOF's half-spaces (a continuous function of x, so the L-G iterations
//     converge as with any fixed PD constraint). The projection is then checked against the real surface: where
//     it is closer than half the thickness (a concave crease, a large slide, a vertex that started far away), a
//     half-space at that closest point (or, when the segment start -> target crosses a triangle from outside,
//     at that triangle: CCD) is added for the rest of the step, up to kMaxPlanes. Without CCD the first
//     half-space comes from the position itself, not from the start.
//     Not the default: on the t-shirt, whose stitches drag panels 5-20 cm per step across the body while it
//     assembles, a tangent plane fixed for the step holds sliding vertices in the air (lifted by d^2 / 2R) and
//     the garment gains energy until it falls off (measured, issue 6); it suits settled garments and creases.
//   Reproject (default): the first version. Every iteration projects x to closest + thickness *
//     normal, or, when the segment x_start -> x crossed a triangle from outside (CCD), to that triangle's
//     closest point + thickness * face normal. The target jumps when the closest triangle changes: on body
//     creases it cycles between targets ~15 mm apart and the L-G iterations stall at their cap.
// Friction: with n the direction of the normal correction, c the normal load as a displacement and u = (I - n
// n^T)(target - x_start) the tangential displacement of the step, the target moves by -u when |u| <= mu c
// (static: the vertex keeps its tangential position) and by -mu c u / |u| otherwise (kinetic: slip reduced by mu
// c). FrictionLoadKind::Inertial: c = the penetration of the inertial prediction z = x + h v + h^2 g into the
// half-spaces (the impulse of momentum and gravity, m c / h); CollisionFree: c = (target - x) . n (also the
// cloth's tension pulling it into the body: a stretch left by a landing presses itself on the body and is
// then held by friction for good).
#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "drape/collision/avatar_collider.h"
#include "drape/pd/contact_solve.h"

namespace drape::pd {

struct AvatarContactOptions {
  double thickness = 0.004;  // metres kept between cloth and collider surface
  double margin = 0.02;      // metres beyond the thickness where vertices are watched
  double weight = 1e6;       // w_k, N/m
  double friction = 0.0;     // Coulomb mu; 0 = frictionless
  bool ccd = true;           // test the step's segments against the collider triangles
  // Keep, within a step, the target a DOF got when it was first found in contact while it stays in contact:
  // a contact target is a discontinuous function of the position (closest triangle, CCD crossing, static or
  // kinetic friction), and re-projecting it every L-G iteration lets vertices on creases of the body cycle
  // between targets centimetres apart, so the L-G iterations never meet their tolerance. Reproject mode: a held
  // DOF is not looked up again in the step; it stays in contact while its collision-free position is behind the
  // plane through its target with the contact normal (it is pressed onto the body), and is let go otherwise.
  bool holdTargets = false;
  ContactTargetKind targets = ContactTargetKind::Reproject;
  FrictionLoadKind frictionLoad = FrictionLoadKind::Inertial;
};

struct AvatarContactStats {
  int watched = 0;         // DOFs looked at (closest-point queries made)
  int contacts = 0;        // constraints added
  int ccdContacts = 0;     // of which found by CCD (the proximity test alone would have missed or flipped them);
                           // StepPlanes: whose collision-free position is behind its half-space's surface plane
  int planesAdded = 0;     // StepPlanes: half-spaces added in this call after the real-surface check
  int staticFriction = 0;  // of which held by static friction
};

class AvatarContacts {
 public:
  AvatarContacts(std::shared_ptr<const collision::AvatarCollider> collider, const AvatarContactOptions& options);

  // Start of a step (forgets the step's half-spaces). start, predicted: |V| x 3 positions at the start of the
  // step and after the inertial prediction; freeVertices: vertex of each free DOF. Keeps the DOFs whose start is closer to the collider than
  // thickness + margin + 2 |predicted - start| as candidates, and for every other DOF a lower bound of its
  // distance to the collider (internal forces, e.g. stitches closing a seam, can move a vertex much farther than
  // its inertial prediction: addConstraints watches those too). A DOF's bound is carried over from its last query,
  // less the distance it has moved since, while that still keeps it out of the candidates; only then is it queried
  // again. The same freeVertices are expected from step to step (a different count starts afresh). A DOF whose
  // start is inside the collider, at any depth (a garment placed through the body), is a candidate; where its
  // collision-free position is deeper than the reach, it is pushed back out through the tangent plane at its
  // start's closest surface point.
  void beginStep(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& predicted,
                 const std::vector<int>& freeVertices);
  bool hasCandidates() const { return !m_candidates.empty(); }
  int candidateCount() const { return static_cast<int>(m_candidates.size()); }

  // Adds the contact constraints at collision-free positions xFree (|free| x 3) to acc. Parallel. A DOF is
  // looked at when it may be in contact: Reproject mode, when it moved at least its start distance bound minus
  // the thickness (closer than that it can neither be within the thickness nor have crossed the surface);
  // StepPlanes mode, when it is a candidate or moved farther than its bound minus thickness + margin.
  AvatarContactStats addConstraints(const Eigen::MatrixX3d& xFree, ContactAccumulator& acc);

  // End of a step: the fail-safe behind the soft constraints above. A contact constraint is one weighted term of
  // the L-G compromise, so a much stiffer term (a rigid bending plate, the stiffest fabric on a coarse mesh) or a
  // step that carries a vertex metres can leave the converged x inside the body. Each free DOF whose end position
  // x.row(freeVertices[d]) is inside the collider deeper than the thickness (and within thickness + margin of the
  // surface; deeper ones, as a garment placed through the body, are left to the constraints) is moved to the
  // closest surface point plus the thickness along the outward normal. DOFs with skip[d] set are left alone. A DOF
  // is looked at only when it started inside or moved at least its start distance bound plus the thickness.
  // Parallel; returns the number moved.
  int resolve(Eigen::MatrixX3d& x, const std::vector<int>& freeVertices, const std::vector<char>* skip = nullptr) const;

  const AvatarContactOptions& options() const { return m_options; }
  // From the next step on (the preview switches both once the garment is sewn, preview_settings.h sewnGap; before
  // that it sets holdTargets per step, by the step's length: holdTargetsStep).
  void setHoldTargets(bool hold) { m_options.holdTargets = hold; }
  void setFrictionLoad(FrictionLoadKind load) { m_options.frictionLoad = load; }

 private:
  static constexpr int kMaxPlanes = 3;
  // Contact half-spaces {y : (y - point[i]) . normal[i] >= thickness} of one DOF within a step.
  struct StepPlanes {
    std::array<Eigen::Vector3d, kMaxPlanes> point, normal;  // metres; unit outward
    int count = 0;
    bool started = false;  // the half-space of the start position has been looked for
  };

  // Earliest collider triangle crossed from outside by the segment p0 -> p1; -1 when none.
  int firstCrossing(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) const;

  // One watched DOF: a candidate of beginStep or a DOF that moved far (addConstraints). kind: 0 none,
  // 1 proximity, 2 CCD, +4 held by static friction. Reproject mode; p0 start, p1 collision-free position, z
  // inertial prediction; normal: the unit contact normal the target was pushed along.
  // nearby: the collider triangles near the DOF's last full query (updated; see AvatarCollider::closest).
  // startInside: p0 is inside the collider, with closest surface point startClosest and outward normal
  // startNormal; p1 deeper than the reach is then pushed back out through that point's tangent plane.
  char constrain(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& z, bool startInside,
                 const Eigen::Vector3d& startClosest, const Eigen::Vector3d& startNormal, Eigen::Vector3d& target,
                 Eigen::Vector3d& normal, collision::NearbyTriangles& nearby) const;
  // StepPlanes mode: the same for free DOF d at collision-free position x (adds to m_planes[d]); added: set to
  // the number of half-spaces added.
  char constrainToPlanes(int d, const Eigen::Vector3d& x, Eigen::Vector3d& target, int& added);
  // x projected into the intersection of the half-spaces (cyclic projections; exact for one plane or two
  // orthogonal ones, within millimetres of it for the shallow creases of a body).
  Eigen::Vector3d projectToPlanes(const StepPlanes& planes, Eigen::Vector3d x) const;
  // Lagged Coulomb friction (header): moves target; c: normal load as a displacement (m), n: unit normal.
  // Returns true when static.
  bool applyFriction(const Eigen::Vector3d& start, const Eigen::Vector3d& n, double c, Eigen::Vector3d& target) const;

  std::shared_ptr<const collision::AvatarCollider> m_collider;
  AvatarContactOptions m_options;
  std::vector<Eigen::Vector3d> m_faceNormals;  // unit, outward, per collider triangle
  std::vector<int> m_candidates;               // free DOF indices
  Eigen::MatrixX3d m_freeStart;                // start position of every free DOF (|free| x 3)
  Eigen::MatrixX3d m_freePredicted;            // inertial prediction z of every free DOF (|free| x 3)
  std::vector<float> m_bound;                  // per free DOF: lower bound of its start distance to the collider
  Eigen::MatrixX3d m_queriedAt;                // per free DOF: where its distance was last queried (beginStep)
  std::vector<double> m_queriedBound;          // per free DOF: the bound found there; -1 = never queried
  std::vector<collision::NearbyTriangles> m_nearby;  // per free DOF: the collider triangles near its last full query
  std::vector<char> m_startInside;             // per free DOF: its start is inside the collider (any depth)
  std::vector<Eigen::Vector3d> m_startClosest;  // per free DOF inside at its start: closest surface point
  std::vector<Eigen::Vector3d> m_startNormal;   // ... and the outward normal there
  std::vector<Eigen::Vector3d> m_held;         // per free DOF: target held in this step (holdTargets)
  std::vector<Eigen::Vector3d> m_heldNormal;   // per free DOF: the held target's contact normal (Reproject)
  std::vector<char> m_heldKind;                // per free DOF: its kind, 0 = none held
  std::vector<StepPlanes> m_planes;            // per free DOF: half-spaces of this step (StepPlanes)
};

}  // namespace drape::pd
