#pragma once
// A simulation-ready garment: every panel meshed into triangles, placed in 3D, with stitches as pairs of
// vertices. Panels are meshed independently, so a stitched seam has a vertex on each side.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace drape {

struct GarmentStitch {
  int stitch = 0;      // index into Pattern::stitches
  int firstPair = 0;   // range [firstPair, firstPair + pairCount) in Garment::stitchPairs
  int pairCount = 0;
  int firstEdgeStitch = 0;  // range in Garment::edgeStitches (non-conforming seams only)
  int edgeStitchCount = 0;
};

// A vertex of one side of a seam sewn to the point (1 - t) x_a + t x_b of the other side's edge (a, b), when the
// two sides were sampled at their own spacing (MeshingOptions::conformingSeams false).
struct GarmentEdgeStitch {
  int vertex = 0;
  int a = 0;
  int b = 0;
  double t = 0.0;  // in [0, 1]
};

struct Garment {
  Eigen::MatrixX2d rest;        // |V| x 2, metres: pattern coordinates (material frame: warp = x, weft = y)
  Eigen::MatrixX2d uvs;         // |V| x 2, texture coordinates: equal to rest (metres, each panel in its own frame)
  Eigen::MatrixX3d positions;   // |V| x 3, metres: placed 3D positions
  // |F| x 3. A panel's outside (the side facing away from the body) is the side from which its outline runs
  // counter-clockwise (GarmentCode's convention): its triangles are counter-clockwise in the pattern plane when
  // the outline is, clockwise when the outline is clockwise, so that every face's normal points outward once placed.
  Eigen::MatrixX3i triangles;
  Eigen::VectorXi trianglePanel;  // |F|, panel index of each triangle
  Eigen::VectorXi vertexPanel;    // |V|, panel index of each vertex
  std::vector<std::string> panelNames;
  // For panel p and its edge e, the boundary vertices along that edge from its start to its end (inclusive);
  // consecutive edges share their corner vertex.
  std::vector<std::vector<std::vector<int>>> edgeVertices;
  std::vector<std::pair<int, int>> stitchPairs;  // vertex pairs sewn together: (side a vertex, side b vertex)
  std::vector<GarmentEdgeStitch> edgeStitches;  // non-conforming seams: vertex to edge point
  std::vector<GarmentStitch> stitches;

  int vertexCount() const { return static_cast<int>(positions.rows()); }
  int triangleCount() const { return static_cast<int>(triangles.rows()); }
};

}  // namespace drape
