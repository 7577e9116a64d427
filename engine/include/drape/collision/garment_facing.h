#pragma once
// Which way a garment's faces point relative to a body: a face near the body whose normal (by its winding) points
// away from the body faces outward, as a garment is worn right side out. Renderers draw a face's back in the
// "inside" colour and exporters carry the winding into other tools, so a panel wound into the body looks missing.
#include <Eigen/Core>

#include "drape/collision/avatar_collider.h"

namespace drape::collision {

struct GarmentFacing {
  int nearFaces = 0;     // faces whose centroid lies outside the body, within nearDistance of it
  int outwardFaces = 0;  // of those, the faces whose normal points away from the body
  int inwardFace = -1;   // the lowest-numbered near face that points into the body; -1: none
  // outwardFaces / nearFaces (1 when no face is near the body).
  double outwardFraction() const { return nearFaces > 0 ? double(outwardFaces) / nearFaces : 1.0; }
};

// positions: |V| x 3, metres; triangles: |F| x 3; nearDistance: metres. A face is outward when its normal has a
// positive component along the gradient of the body's signed distance at its centroid.
GarmentFacing garmentFacing(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& triangles,
                            const AvatarCollider& body, double nearDistance);

}  // namespace drape::collision
