#pragma once
// Cloth-avatar contact constraints of the PD preview (pd-dd sections 6, 7.3): one position constraint (A_k = I)
// per garment vertex that is within the contact thickness of the collider, or whose path over the step crossed
// the collider surface (continuous collision detection), with a lagged Coulomb friction correction of the target.
//   Proximity: the collision-free position x is projected to closest + thickness * normal (pseudo-normal sign).
//   CCD:       the segment x_start -> x is tested against the collider triangles it overlaps with the cubic CCD
//              of collision/ccd.h (static triangle). The earliest triangle crossed from its outer side wins; the
//              target is its closest point to x plus thickness * its face normal, so a vertex that moved through
//              the collider within the step is pushed back to the side it came from (no tunnelling).
//   Friction:  with c = (target - x) . n the normal correction and u = (I - n n^T)(target - x_start) the
//              tangential displacement of the step, the target moves by -u when |u| <= mu c (static: the vertex
//              keeps its tangential position) and by -mu c u / |u| otherwise (kinetic: slip reduced by mu c).
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "drape/pd/contact_solve.h"

namespace drape::collision {
class AvatarCollider;
}

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
  // between targets centimetres apart, so the L-G iterations never meet their tolerance.
  bool holdTargets = false;
};

struct AvatarContactStats {
  int contacts = 0;        // constraints added
  int ccdContacts = 0;     // of which found by CCD (the proximity test alone would have missed or flipped them)
  int staticFriction = 0;  // of which held by static friction
};

class AvatarContacts {
 public:
  AvatarContacts(std::shared_ptr<const collision::AvatarCollider> collider, const AvatarContactOptions& options);

  // Start of a step. start, predicted: |V| x 3 positions at the start of the step and after the inertial
  // prediction; freeVertices: vertex of each free DOF. Keeps the DOFs whose start is closer to the collider than
  // thickness + margin + 2 |predicted - start| as candidates, and for every other DOF a lower bound of its
  // distance to the collider (internal forces, e.g. stitches closing a seam, can move a vertex much farther than
  // its inertial prediction: addConstraints watches those too).
  void beginStep(const Eigen::MatrixX3d& start, const Eigen::MatrixX3d& predicted,
                 const std::vector<int>& freeVertices);
  bool hasCandidates() const { return !m_candidates.empty(); }
  int candidateCount() const { return static_cast<int>(m_candidates.size()); }

  // Adds the constraints of the candidates, and of the other DOFs whose collision-free position moved farther
  // from the step's start than their distance bound minus thickness + margin, at collision-free positions xFree
  // (|free| x 3) to acc. Parallel.
  AvatarContactStats addConstraints(const Eigen::MatrixX3d& xFree, ContactAccumulator& acc);

  const AvatarContactOptions& options() const { return m_options; }

 private:
  // Earliest collider triangle crossed from outside by the segment p0 -> p1; -1 when none.
  int firstCrossing(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) const;

  // One watched DOF: a candidate of beginStep or a DOF that moved far (addConstraints). kind: 0 none,
  // 1 proximity, 2 CCD, +4 held by static friction.
  char constrain(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, Eigen::Vector3d& target) const;

  std::shared_ptr<const collision::AvatarCollider> m_collider;
  AvatarContactOptions m_options;
  std::vector<Eigen::Vector3d> m_faceNormals;  // unit, outward, per collider triangle
  std::vector<int> m_candidates;               // free DOF indices
  Eigen::MatrixX3d m_freeStart;                // start position of every free DOF (|free| x 3)
  std::vector<float> m_bound;                  // per free DOF: lower bound of its start distance to the collider
  std::vector<Eigen::Vector3d> m_held;         // per free DOF: target held in this step (holdTargets)
  std::vector<char> m_heldKind;                // per free DOF: its kind, 0 = none held
};

}  // namespace drape::pd
