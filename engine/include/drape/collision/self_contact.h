#pragma once
// Cloth-cloth contact for the Newton drape (newton-drape-pizana 3.2-3.3): quadratic penalty on every
// non-adjacent vertex-triangle and edge-edge pair closer than the thickness,
//   E(x) = sum_pairs 0.5 k (thickness - d_pair(x))^2,  d_pair = unsigned distance between the closest points.
// Exact for every x: candidate pairs are gathered through the BVH within thickness + margin around reference
// positions x_ref; as long as no vertex has moved more than margin / 2 from x_ref no other pair can be within
// the thickness, so evaluations only loop over candidates. A larger move triggers a new BVH query around x.
#include <Eigen/Core>
#include <mutex>
#include <utility>
#include <vector>

#include "drape/collision/avatar_contact.h"
#include "drape/collision/contact_stencil.h"
#include "drape/collision/self_proximity.h"
#include "drape/model/cloth_model.h"
#include "drape/newton/energy.h"

namespace drape::collision {

// Vertex pairs that count as one vertex in cloth-cloth contact (a closed seam must not repel itself): the
// vertex-to-vertex stitch pairs as given, then for every edge stitch (vertex sewn to (1 - t) x_a + t x_b of a
// non-conforming seam) the vertex with the nearer endpoint of its edge (a when t <= 1/2, else b). The nearer
// endpoint already excludes every triangle of the edge (each holds both endpoints). Not both endpoints: merged
// vertices form groups (union-find), and consecutive stitches on one edge would chain every vertex of the seam
// into one group, so a seam folded onto itself would never collide. With the nearer endpoint each coarse-side
// vertex gathers the fine-side vertices within half an edge of it, and groups never chain along the seam.
std::vector<std::pair<int, int>> contactMergedVertices(const std::vector<std::pair<int, int>>& stitchPairs,
                                                       const std::vector<model::EdgeStitch>& edgeStitches);

class SelfContactEnergy : public newton::Energy {
 public:
  // triangles: garment triangles; mergedVertices: stitched vertex pairs (never repel); margin: metres >= 0,
  // search radius beyond the thickness (default 0: the thickness itself, i.e. margin = thickness).
  SelfContactEnergy(const Eigen::MatrixX3i& triangles, int vertexCount,
                    const std::vector<std::pair<int, int>>& mergedVertices, ContactParameters params,
                    double margin = 0.0);

  std::string_view name() const override { return "self_contact"; }
  void beginStep(const newton::StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, newton::BlockMatrix& h) const override;

  // Pairs within the thickness at x as 4-vertex stencils (distance > 0, normal from the second primitive to the
  // first). Used by friction.
  std::vector<ContactStencil> contacts(const Eigen::VectorXd& x) const;
  // Candidate pairs currently held (vertex-triangle + edge-edge) and number of BVH queries so far.
  int candidateCount() const { return static_cast<int>(m_vertexTriangle.size() + m_edgeEdge.size()); }
  int queryCount() const { return m_queries; }
  const ContactParameters& parameters() const { return m_params; }

 private:
  struct Evaluated {
    std::array<int, 4> vertices{};
    double energy = 0.0;
    Vector12d gradient;
    Matrix12d hessian;
    SquaredDistanceDerivatives distance;
  };
  void ensureCandidates(const Eigen::VectorXd& x) const;
  // Active pairs at x with their penalty derivatives (Hessian only when wanted).
  std::vector<Evaluated> evaluate(const Eigen::VectorXd& x, bool withHessian) const;

  ContactParameters m_params;
  double m_margin = 0.0;
  mutable std::mutex m_mutex;
  mutable SelfProximity m_proximity;
  mutable Eigen::VectorXd m_reference;  // positions the candidates were gathered at
  mutable std::vector<VertexTrianglePair> m_vertexTriangle;
  mutable std::vector<EdgeEdgePair> m_edgeEdge;
  mutable int m_queries = 0;
};

}  // namespace drape::collision
