#pragma once
// Loads a body or collider (OBJ, glTF/GLB, FBX, PLY, STL) through assimp into one triangle mesh in metres.
// Empty meshes, non-finite coordinates and bad indices raise InputError naming the file; degenerate faces are
// dropped with one warning that counts them.
#include <filesystem>
#include <string>

#include "drape/avatar/avatar_units.h"
#include "drape/core/diagnostics.h"
#include "drape/geometry/triangle_mesh.h"

namespace drape {

// unitsInMeter: file units per metre (1 = metres, 100 = centimetres, 1000 = millimetres, unitsInMeterFromName);
// must be > 0.
// Node transforms are applied (multi-node glTF/FBX come out assembled), polygons are triangulated, all meshes
// are merged, and corners at bitwise-equal positions are welded into one vertex (also across meshes), so a file
// with two distinct vertices at the same point yields one. Unused vertices are dropped. Faces wound inward (a
// whole part inside out, or single faces against their neighbours) are turned outward (mesh_orientation.h) with
// one warning. Errors ("<file>: ..."): file not found, not a regular file, cannot read mesh (assimp's reason), contains
// no triangles, non-finite coordinate (OBJ: line and 1-based vertex number), face refers to a vertex out of range
// (OBJ: line and face number). Degenerate faces (repeated vertex, zero area) are dropped with one warning in
// diagnostics, if given. A body whose height along y is not a human body's gets one warning there too
// (avatarHeightWarning: it names the unit that would make it one, and the unit an FBX file declares).
TriangleMesh loadAvatar(const std::filesystem::path& file, double unitsInMeter = 1.0,
                        Diagnostics* diagnostics = nullptr);

}  // namespace drape
