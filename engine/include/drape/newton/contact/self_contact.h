#pragma once
// Cloth-cloth contact for the Newton drape (newton-drape-pizana 3.2-3.3): quadratic penalty on every
// non-adjacent vertex-triangle and edge-edge pair closer than the thickness,
//   E(x) = sum_pairs 0.5 k (thickness - d_pair(x))^2,  d_pair = unsigned distance between the closest points.
// Exact for every x: candidate pairs are gathered through the BVH within thickness + margin around reference
// positions x_ref; as long as no vertex has moved more than margin / 2 from x_ref no other pair can be within
// the thickness, so evaluations only loop over candidates, from step to step while the cloth moves little. A larger
// move triggers a new BVH query around x.
// A penalty cannot tell the two sides of a crossing apart: where the cloth already passes through itself it would
// hold the tangle in place. So at the start of every step the triangles that cross another are found, and the pairs
// with a vertex on them take no part in this term during the step. Nor do the pairs with a vertex on a side that the
// crossing triangles cut off from the rest of their piece of cloth (all but the side with the most triangles): the tip
// of a fold pushed through another layer lies wholly on the wrong side, and its contacts there would push it further
// in. The cloth's own forces and the intersection contour pull such a tangle free.
// Two triangles that share no vertex and did not cross at the last step's start can cross at this one only if they
// touched in between, through a vertex-triangle or edge-edge pair: while the candidates have been valid for both
// states (and so for the straight path between them), only the last crossings and the triangles of the candidates
// are tested; after a new query, every triangle.
#include <Eigen/Core>
#include <mutex>
#include <utility>
#include <vector>

#include "drape/collision/contact_merged_vertices.h"
#include "drape/collision/contact_stencil.h"
#include "drape/collision/self_proximity.h"
#include "drape/model/cloth_model.h"
#include "drape/newton/contact/avatar_contact.h"
#include "drape/newton/energy.h"

namespace drape::newton {

class SelfContactEnergy : public Energy {
 public:
  // triangles: garment triangles; mergedVertices: stitched vertex pairs (never repel); margin: metres >= 0,
  // search radius beyond the thickness (default 0: the thickness itself, i.e. margin = thickness).
  SelfContactEnergy(const Eigen::MatrixX3i& triangles, int vertexCount,
                    const std::vector<std::pair<int, int>>& mergedVertices, ContactParameters params,
                    double margin = 0.0);

  std::string_view name() const override { return "self_contact"; }
  void beginStep(const StepContext& ctx) override;
  double value(const Eigen::VectorXd& x) const override;
  void addGradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void addHessian(const Eigen::VectorXd& x, BlockMatrix& h) const override;

  // Pairs within the thickness at x as 4-vertex stencils (distance > 0, normal from the second primitive to the
  // first). Used by friction.
  std::vector<collision::ContactStencil> contacts(const Eigen::VectorXd& x) const;
  // Candidate pairs currently held (vertex-triangle + edge-edge) and number of BVH queries so far.
  int candidateCount() const { return static_cast<int>(m_vertexTriangle.size() + m_edgeEdge.size()); }
  int queryCount() const { return m_queries; }
  // The pairs of triangles (t < u) that crossed at the start of the step; the garment's triangles; the representative
  // of a vertex's stitched group (triangles sharing one are neighbours).
  const std::vector<std::pair<int, int>>& crossings() const { return m_crossings; }
  const Eigen::MatrixX3i& triangles() const { return m_proximity.triangles(); }
  int canonical(int v) const { return m_proximity.canonical(v); }
  const ContactParameters& parameters() const { return m_params; }

 private:
  struct Evaluated {
    std::array<int, 4> vertices{};
    double energy = 0.0;
    collision::Vector12d gradient;
    collision::Matrix12d hessian;
    collision::SquaredDistanceDerivatives distance;
  };
  void ensureCandidates(const Eigen::VectorXd& x) const;
  // The crossing pairs at x among the last step's crossings and the triangle pairs of the candidates.
  std::vector<std::pair<int, int>> crossingsNearCandidates(const Eigen::VectorXd& x) const;
  // Connected components of the included triangles (neighbours across edges and stitched seams): a component id per
  // triangle, -1 where not included.
  std::vector<int> components(const std::vector<char>& included) const;
  // m_excluded from m_crossings: the vertices of the crossing triangles and of every side they cut off.
  void excludeAroundCrossings();
  // Active pairs at x with their penalty derivatives (Hessian only when wanted).
  std::vector<Evaluated> evaluate(const Eigen::VectorXd& x, bool withHessian) const;

  ContactParameters m_params;
  double m_margin = 0.0;
  mutable std::mutex m_mutex;
  mutable collision::SelfProximity m_proximity;
  std::vector<std::pair<int, int>> m_merged;     // stitched vertex pairs, one vertex for crossings too
  std::vector<std::pair<int, int>> m_crossings;  // triangle pairs crossing at the start of the step
  std::vector<char> m_excluded;                  // per vertex: on a crossing triangle at the start of the step
  mutable Eigen::VectorXd m_reference;           // positions the candidates were gathered at
  mutable std::vector<collision::VertexTrianglePair> m_vertexTriangle;
  mutable std::vector<collision::EdgeEdgePair> m_edgeEdge;
  mutable int m_queries = 0;
  int m_crossingsAtQuery = -1;  // m_queries when the crossings were last found (-1: never)
  // The triangles around each vertex and each edge of SelfProximity::edges(): [start[i], start[i + 1]).
  std::vector<int> m_vertexTriangleStart, m_vertexTriangles, m_edgeTriangleStart, m_edgeTriangles;
  std::vector<int> m_neighbourStart, m_neighbours;  // the triangles sharing an edge with each triangle
  std::vector<int> m_piece;                          // per triangle: its connected piece of cloth
};

}  // namespace drape::newton
