#pragma once
// Turns the triangles of a loaded body outward. Exporters often wind faces inward (a mirroring node transform, a
// flipped export option) or flip some faces only; the collider takes the inside of the body from the winding, so
// such a body would pull the garment into it.
#include "drape/geometry/triangle_mesh.h"

namespace drape {

struct OrientationRepair {
  int facesTurned = 0;     // faces whose winding was reversed
  int partsInsideOut = 0;  // parts whose every face was reversed (the whole part was wound inward)
};

// Per part (faces connected through edges shared by exactly two faces): makes the winding consistent with the
// part's first face, then turns the whole part over when it encloses a clearly negative volume (below -1 % of
// area^1.5; a sheet or a plane encloses none and keeps its winding). Vertices are not moved.
OrientationRepair orientOutward(TriangleMesh& mesh);

}  // namespace drape
