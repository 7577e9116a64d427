#include "drape/collision/garment_facing.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Geometry>

namespace drape::collision {

GarmentFacing garmentFacing(const Eigen::MatrixX3d& positions, const Eigen::MatrixX3i& triangles,
                            const AvatarCollider& body, double nearDistance) {
  return tbb::parallel_reduce(
      tbb::blocked_range<Eigen::Index>(0, triangles.rows()), GarmentFacing{},
      [&](const tbb::blocked_range<Eigen::Index>& range, GarmentFacing facing) {
        for (Eigen::Index f = range.begin(); f < range.end(); ++f) {
          const Eigen::Vector3d a = positions.row(triangles(f, 0)), b = positions.row(triangles(f, 1)),
                                c = positions.row(triangles(f, 2));
          SurfacePoint s;
          if (!body.closest((a + b + c) / 3.0, s, nearDistance) || s.signedDistance < 0.0) continue;
          ++facing.nearFaces;
          if ((b - a).cross(c - a).dot(s.normal) > 0.0)
            ++facing.outwardFaces;
          else if (facing.inwardFace < 0)
            facing.inwardFace = static_cast<int>(f);
        }
        return facing;
      },
      [](GarmentFacing x, const GarmentFacing& y) {
        x.nearFaces += y.nearFaces;
        x.outwardFaces += y.outwardFaces;
        if (x.inwardFace < 0 || (y.inwardFace >= 0 && y.inwardFace < x.inwardFace)) x.inwardFace = y.inwardFace;
        return x;
      });
}

}  // namespace drape::collision
