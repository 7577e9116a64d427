#pragma once
// Simple closed meshes used as colliders and in tests (a sphere, a box), and two checks on closed meshes.
#include <Eigen/Core>

#include "drape/geometry/triangle_mesh.h"

namespace drape {

// Icosahedron subdivided `subdivisions` times (each step splits every triangle into four) with the vertices
// projected onto the sphere. center, radius: metres; radius > 0, 0 <= subdivisions <= 8.
// Result: 10 * 4^s + 2 vertices, 20 * 4^s triangles, closed, counter-clockwise seen from outside.
TriangleMesh makeIcosphere(const Eigen::Vector3d& center, double radius, int subdivisions);

// Axis-aligned box with corners min and max (metres, min < max componentwise): 8 vertices, 12 triangles,
// closed, counter-clockwise seen from outside.
TriangleMesh makeBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max);

// True when every undirected edge is used by exactly two triangles, once in each direction (so the mesh is
// closed and consistently oriented), and no triangle repeats a vertex index or indexes outside the vertices.
// Non-manifold vertices (two cones touching at a point) are not detected.
bool isClosedManifold(const TriangleMesh& mesh);

// Signed volume enclosed by the mesh (m^3): sum over triangles of det(a - o, b - o, c - o) / 6, o = bounds
// centre. Positive when a closed mesh is oriented counter-clockwise seen from outside; meaningless if open.
double signedVolume(const TriangleMesh& mesh);

}  // namespace drape
