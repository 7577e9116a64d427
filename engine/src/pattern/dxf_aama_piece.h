#pragma once
// Private: one DXF-AAMA piece as libdxflib hands it over (the entities of one BLOCK, by layer) and its
// conversion to a validated Panel. Coordinates in file units.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "drape/core/diagnostics.h"
#include "drape/pattern/pattern.h"

namespace drape::detail {

// A POLYLINE, LWPOLYLINE, LINE (two points, open) or POINT (one point).
struct DxfPolyline {
  std::string layer;
  std::vector<Eigen::Vector2d> points;
  std::vector<double> bulges;  // per point: the arc from it to the next point, tan(sweep / 4); 0 = straight
  bool closed = false;
};

struct DxfBlock {
  std::string name;
  std::vector<DxfPolyline> polylines;  // in file order
  std::vector<std::string> texts;      // TEXT and MTEXT lines
  std::vector<std::string> skipped;    // "SPLINE on layer 1": entities not read
  std::string badNumber;               // the first non-finite number, or empty
};

// The panel of one piece called name: vertices and edges from the layer-1 boundary, counter-clockwise; grain line,
// notches and internal lines from layers 7, 4 (and 80-85) and 8. unitsInMeter only sets the size limits.
// Throws InputError "<source>: piece '<name>': <problem>".
Panel buildAamaPanel(const DxfBlock& block, const std::string& name, double unitsInMeter, const std::string& source,
                     Diagnostics& diagnostics);

}  // namespace drape::detail
