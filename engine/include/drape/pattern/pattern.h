#pragma once
// A sewing pattern in GarmentCode's JSON specification: flat 2D panels, each placed in 3D by a
// translation and an XYZ Euler rotation, and stitches joining pairs of panel edges.
// Coordinates here are in the file's units; Pattern::unitsInMeter converts (100 = centimetres).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace drape {

// The shape of one panel edge between its two endpoints.
// Control points are stored as in the file with curvature_coords = "relative": x runs along the edge from
// start (0) to end (1), y is perpendicular as a fraction of the edge length (positive to the left of the
// start -> end direction in GarmentCode's convention; see pattern/edge_curve.h for the exact mapping).
enum class CurveType { Straight, Quadratic, Cubic, Circle };

struct EdgeCurve {
  CurveType type = CurveType::Straight;
  std::vector<Eigen::Vector2d> controls;  // Quadratic: 1 point, Cubic: 2 points (relative coordinates)
  double radius = 0.0;                    // Circle: radius in file units
  bool largeArc = false;                  // Circle: SVG large-arc flag
  bool right = false;                     // Circle: SVG sweep (arc bulges to the right of start -> end)
};

struct PanelEdge {
  int start = 0;  // index into Panel::vertices
  int end = 0;
  EdgeCurve curve;
  std::string label;  // optional "label" of the edge in the file (used to name pins)
};

struct Panel {
  std::string name;
  std::string label;                      // optional panel "label"
  std::vector<Eigen::Vector2d> vertices;  // 2D outline corners, file units
  std::vector<PanelEdge> edges;           // closed loop: edges[i].end == edges[i+1].start
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // file units
  Eigen::Vector3d rotationDeg = Eigen::Vector3d::Zero();  // XYZ Euler angles, degrees
  // Markings in the panel's 2D frame, file units. The pattern view, the printouts and DXF-AAMA carry them; the
  // grain line, when given, is the warp direction (otherwise the warp runs along the panel's x axis).
  std::optional<std::array<Eigen::Vector2d, 2>> grainLine;  // from, to
  std::vector<Eigen::Vector2d> notches;                     // points on the outline
  std::vector<std::vector<Eigen::Vector2d>> internalLines;  // open polylines: darts, placement and fold lines
};

struct StitchSide {
  int panel = 0;  // index into Pattern::panels
  int edge = 0;   // index into Panel::edges
};

struct Stitch {
  StitchSide a;
  StitchSide b;
  // false (the default): a's start meets b's end, as when two panels are sewn face to face;
  // true ("right_wrong" in the file): a's start meets b's start.
  // Checked on the shared GarmentCode files: with the default, paired placed points of every stitch longer than
  // 3 cm differ by a near-rigid translation; the reversed pairing does not. (No file there uses right_wrong.)
  bool rightWrong = false;
};

struct Pattern {
  std::string source;          // file name used in messages
  double unitsInMeter = 100.0;  // file units per metre (100: centimetres)
  std::vector<Panel> panels;    // in panel_order when the file gives one, else file order
  std::vector<Stitch> stitches;

  // Index of the panel called name, or -1.
  int panelIndex(const std::string& name) const {
    for (size_t i = 0; i < panels.size(); ++i)
      if (panels[i].name == name) return static_cast<int>(i);
    return -1;
  }
};

}  // namespace drape
