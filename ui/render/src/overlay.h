#pragma once
// 2D overlay geometry in pixels from the top-left corner: rectangles, gradients, bitmap text and the
// strain legend. Built on the CPU, drawn by the renderer with shaders/overlay.*.
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace drape::render {

struct OverlayVertex {
  float x, y;        // pixels, top-left origin
  float r, g, b, a;  // display RGBA
};

class OverlayBuilder {
 public:
  void addRect(float x0, float y0, float x1, float y1, const Eigen::Vector4f& color);
  // A rectangle whose colour goes linearly from top to bottom.
  void addVerticalGradient(float x0, float y0, float x1, float y1, const Eigen::Vector4f& top,
                           const Eigen::Vector4f& bottom);
  // Bitmap text (bitmap_font.h) with its top-left corner at (x, y); one square per ink pixel.
  void addText(float x, float y, std::string_view text, int scale, const Eigen::Vector4f& color);

  const std::vector<OverlayVertex>& vertices() const { return m_vertices; }
  bool empty() const { return m_vertices.empty(); }

 private:
  std::vector<OverlayVertex> m_vertices;  // triangles, 6 vertices per rectangle
};

// "12.5%": a stretch fraction as a percentage with at most one decimal.
std::string formatPercent(double fraction);

// Strain legend in the top-right corner of a width x height image: title, colour bar, five labelled ticks.
void addStrainLegend(OverlayBuilder& overlay, int width, int height, double strainMin, double strainMax);
// A one-line note ("NO STRAIN DATA") in the top-right corner.
void addCornerNote(OverlayBuilder& overlay, int width, int height, std::string_view text);

}  // namespace drape::render
