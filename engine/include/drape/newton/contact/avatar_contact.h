#pragma once
// Garment-avatar contact for the Newton drape (newton-drape-pizana 3.2: quadratic penalty, stiffness k), with
// gap g_v = thickness - d_v(x) over vertices with signed distance d_v(x) < thickness:
//   E_v = 0.5 k g^2                                  while the vertex is outside the body (0 <= d < thickness),
//   E_v = 0.5 k t^2 + k t u + 0.5 k_in u^2, u = -d    once it is inside (d < 0; t = thickness),
// C1 at d = 0. The soft band outside models the fabric's thickness (the paper's k = 1e2 N/m); inside, the much
// stiffer k_in makes the body's surface a wall. A single k was not enough: a garment whose seams close across
// the body (GarmentCode patterns placed around the body with 20-45 cm gaps) pulls its stitched vertices with
// forces of tens of newtons, and a 1e2 N/m penalty let them settle several centimetres inside the body.
// The contact set is recomputed from x on every evaluation, so E is one fixed function of x and the line search
// compares like with like. This stays cheap because the signed distance is 1-Lipschitz: beginStep stores each
// vertex's signed distance d0 at the step start, and a vertex that moved by less than d0 - thickness since then
// provably has no contact and is skipped without a query. beginStep itself queries only vertices that may be
// near the body: a vertex found outside at the last step start carries the lower bound d0 - (its motion since)
// instead, as long as that bound keeps it clear of the contact band by a margin. Queries are bounded by
// searchRadius: the energy is that of vertices with -searchRadius < d < thickness. Results for the last x are
// cached so that value, gradient and Hessian at the same x share one set of queries. Each vertex keeps the avatar
// triangles near its last full query (collision::AvatarCollider::closest with collision::NearbyTriangles): a vertex
// near the body moves little between evaluations, so most queries are settled by that short list instead of a search.
#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <vector>

#include "drape/collision/avatar_collider.h"
#include "drape/collision/contact_stencil.h"
#include "drape/newton/energy.h"

namespace drape::newton {

struct ContactParameters {
  double stiffness = 1e2;      // k, N/m per contact (paper: 10^2)
  double thickness = 2e-3;     // contact distance, metres (> 0)
  bool projectHessian = true;  // drop the indefinite curvature part of the Hessian (keep it SPD)
  // Avatar contact only: the penalty stiffness inside the body is stiffness x insideStiffnessFactor (>= 1;
  // 1 gives the paper's single quadratic penalty).
  double insideStiffnessFactor = 100.0;
  // Avatar contact only: distance queries look no farther than this (metres, > thickness). Vertices deeper
  // inside the avatar than this are not pushed out (they are lost causes that a penalty would tear through the
  // body), and far vertices cost almost nothing to query.
  double searchRadius = 0.05;
};

// The insideStiffnessFactor for a scene whose stiffest fabric stretches with largestStretch N/m: p's own factor,
// raised so that inside the body the penalty is at least 2 x that stiffness. A fabric that cannot stretch passes
// the stitches' pull (stitch stiffness x seam gap) on to the body undiminished and otherwise presses itself into
// it. Every fabric preset (at most 2e4 N/m) keeps the default factor at the default stiffness (1e3 N/m).
double insideStiffnessFactorFor(const ContactParameters& p, double largestStretch);

// The penalty above as a function of the signed distance d: energy, force dE/dg (g = thickness - d, so the force
// pushes outwards when positive) and stiffness d2E/dg2. Shared with the avatar's feature contact.
struct AvatarPenalty {
  double stiffness = 1e2;
  double thickness = 2e-3;
  double insideStiffnessFactor = 100.0;
  explicit AvatarPenalty(const ContactParameters& p)
      : stiffness(p.stiffness), thickness(p.thickness), insideStiffnessFactor(p.insideStiffnessFactor) {}
  double energy(double distance) const;
  double force(double distance) const;
  double stiffnessAt(double distance) const;
};

class AvatarContactEnergy : public Energy {
 public:
  // vertexCount: garment vertices; collider shared with other users (the PD preview, statistics).
  AvatarContactEnergy(std::shared_ptr<const collision::AvatarCollider> collider, int vertexCount,
                      ContactParameters params);

  std::string_view name() const override { return "avatar_contact"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;
  // No vertex deeper inside the body than the contact thickness (a vertex already that deep at the step start aside).
  bool satisfied(const Eigen::VectorXd& x) const override;

  // Vertices with signed distance < thickness at x: one-vertex stencils (weight 1), distance signed, normal the
  // outward gradient of the signed distance. Used by friction for its normal forces.
  const std::vector<collision::ContactStencil>& contacts(const Eigen::VectorXd& x) const;
  // Vertices whose contact query could not be skipped in the last evaluation (for statistics).
  int lastQueryCount() const { return m_lastQueries; }
  // Vertices the last beginStep queried (the others kept a lower bound; for statistics and tests).
  int lastStartQueryCount() const { return m_lastStartQueries; }
  const ContactParameters& parameters() const { return m_params; }
  const collision::AvatarCollider& collider() const { return *m_collider; }

 private:
  struct Active {
    collision::ContactStencil stencil;
    double curvature = 0.0;  // Hessian of the signed distance = curvature * (P - n n^T), P below
    Eigen::Matrix3d complement = Eigen::Matrix3d::Zero();  // projector off the closest feature's span
  };
  void update(const Eigen::VectorXd& x) const;

  std::shared_ptr<const collision::AvatarCollider> m_collider;
  int m_vertexCount = 0;
  ContactParameters m_params;
  AvatarPenalty m_penalty;
  // What m_startDistance holds for a vertex: its signed distance (Exact), a lower bound on it (Lower), or the
  // search radius because nothing was found within it (Far: deeper inside than the radius; a vertex found outside
  // beyond the radius keeps its exact distance).
  enum class StartKind : char { Far, Exact, Lower };
  // beginStep keeps a lower bound instead of querying while it exceeds thickness + this margin (metres): the
  // vertex then needs no query in the step unless it moves by more than the margin within it.
  static constexpr double kLowerBoundMargin = 5e-3;
  Eigen::VectorXd m_startPositions;     // x at the last beginStep (empty before the first)
  std::vector<double> m_startDistance;  // signed distance at m_startPositions per vertex (see m_startKind)
  std::vector<StartKind> m_startKind;
  mutable std::vector<collision::NearbyTriangles> m_nearby;  // per vertex: the triangles near its last full query
  mutable std::mutex m_mutex;
  mutable Eigen::VectorXd m_cachedX;
  mutable std::vector<Active> m_active;
  mutable std::vector<collision::ContactStencil> m_stencils;
  mutable int m_lastQueries = 0;
  int m_lastStartQueries = 0;
};

}  // namespace drape::newton
