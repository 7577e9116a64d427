#pragma once
// An owned copy of everything needed to draw or export the current state: safe to hand to another thread.
// The renderer reads it and computes nothing physical: strain, domains and contacts arrive here precomputed.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "drape/geometry/triangle_mesh.h"
#include "drape/sim/stage.h"

namespace drape {

struct Snapshot {
  // Garment
  Eigen::MatrixX3d positions;      // |V| x 3, metres
  Eigen::MatrixX3i triangles;      // |F| x 3
  Eigen::MatrixX2d uvs;            // |V| x 2 pattern coordinates (metres), may be empty
  Eigen::VectorXi trianglePanel;   // |F| panel index, may be empty
  std::vector<Eigen::Vector3f> panelColors;  // linear RGB in [0, 1] per panel, may be empty (renderer picks)
  Eigen::VectorXd triangleStrain;  // |F| stretch relative to rest (0.05 = 5%), may be empty
  Eigen::VectorXi triangleDomain;  // |F| preview-solver domain, may be empty
  Eigen::VectorXi vertexContact;   // |V| 1 where the vertex is in contact, may be empty
  // Colliders
  TriangleMesh avatar;             // may have no triangles
  // Metres: cloth this close to a collider rests on it (the contact thickness). The renderer draws the colliders
  // this far inside their surface, so that cloth resting within the contact band is never hidden by the body.
  double contactThickness = 0.0;
  // State
  double time = 0.0;               // simulated seconds
  Stage stage = Stage::Placed;

  BoundingBox bounds() const {
    BoundingBox b = boundsOf(positions);
    b.extend(boundsOf(avatar.vertices));
    return b;
  }
};

}  // namespace drape
