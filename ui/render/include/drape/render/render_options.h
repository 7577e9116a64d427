#pragma once
// What to draw and how: display mode, overlays, output size, background and anti-aliasing.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "drape/render/image.h"

namespace drape::render {

enum class DisplayMode {
  Shaded,     // per-panel colours (Snapshot::panelColors, or a built-in palette), two-sided lighting
  Wireframe,  // light neutral fabric with every triangle edge drawn
  Strain,     // per-triangle stretch heat map (Snapshot::triangleStrain) with a legend in %
  Domains,    // preview-solver partition colours (Snapshot::triangleDomain)
  Contacts,   // neutral fabric, vertices in contact (Snapshot::vertexContact) highlighted
  Print,      // RenderOptions::print laid on the garment by its pattern coordinates (Snapshot::uvs), as cut
};

std::string_view displayModeName(DisplayMode mode);  // "shaded", "wireframe", ...
// Parses "shaded|wireframe|strain|domains|contacts|print"; nullopt for anything else.
std::optional<DisplayMode> parseDisplayMode(std::string_view name);

struct RenderOptions {
  DisplayMode mode = DisplayMode::Shaded;
  bool wireframeOverlay = false;  // draw triangle edges over any mode
  int width = 1024;               // pixels
  int height = 1024;              // pixels
  Eigen::Vector3f background{0.93f, 0.94f, 0.96f};  // display RGB at the top of the vertical gradient
  int msaaSamples = 4;            // 0 or 1 disables multisampling; clamped to what the context supports
  bool showGround = true;         // ground plane with a grid below the scene bounds
  bool showAvatar = true;
  bool showLegend = true;         // strain legend (strain mode only)
  // Strain colour scale, as stretch fractions (0.05 = 5%). strainMax <= strainMin picks the maximum of the
  // snapshot's strain rounded up to a readable step (1, 2, 5 x 10^k %).
  double strainMin = 0.0;
  double strainMax = -1.0;
  // Print mode: the fabric's print, repeated over every panel in its own pattern frame (x along the panel's x, the
  // image's top towards the panel's +y), printWidth metres of cloth per image width. Without an image, neutral.
  std::shared_ptr<const Image> print;
  double printWidth = 0.25;
};

}  // namespace drape::render
