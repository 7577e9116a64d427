#pragma once
// Loads a body or collider (OBJ, glTF/GLB, FBX, PLY, STL) through assimp into one triangle mesh in metres.
// Empty meshes, non-finite coordinates and bad indices raise InputError naming the file; degenerate faces are
// dropped with one warning that counts them.
#include <filesystem>

#include "drape/core/diagnostics.h"
#include "drape/geometry/triangle_mesh.h"

namespace drape {

// unitsInMeter: file units per metre (1 = metres, 100 = centimetres, 1000 = millimetres).
TriangleMesh loadAvatar(const std::filesystem::path& file, double unitsInMeter = 1.0,
                        Diagnostics* diagnostics = nullptr);

// "m" -> 1, "cm" -> 100, "mm" -> 1000; anything else raises InputError.
double unitsInMeterFromName(const std::string& name);

}  // namespace drape
