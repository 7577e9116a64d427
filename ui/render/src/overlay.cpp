#include "overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bitmap_font.h"
#include "drape/render/palette.h"

namespace drape::render {
namespace {

int legendScale(int height) { return std::clamp(static_cast<int>(std::lround(height / 360.0)), 1, 4); }

Eigen::Vector4f opaque(const Eigen::Vector3f& c) { return {c.x(), c.y(), c.z(), 1.0f}; }

}  // namespace

void OverlayBuilder::addRect(float x0, float y0, float x1, float y1, const Eigen::Vector4f& color) {
  addVerticalGradient(x0, y0, x1, y1, color, color);
}

void OverlayBuilder::addVerticalGradient(float x0, float y0, float x1, float y1, const Eigen::Vector4f& top,
                                         const Eigen::Vector4f& bottom) {
  auto v = [&](float x, float y, const Eigen::Vector4f& c) {
    m_vertices.push_back({x, y, c.x(), c.y(), c.z(), c.w()});
  };
  v(x0, y0, top), v(x1, y0, top), v(x1, y1, bottom);
  v(x0, y0, top), v(x1, y1, bottom), v(x0, y1, bottom);
}

void OverlayBuilder::addText(float x, float y, std::string_view text, int scale, const Eigen::Vector4f& color) {
  for (size_t i = 0; i < text.size(); ++i) {
    const float gx = x + static_cast<float>(i * kGlyphAdvance * scale);
    for (int row = 0; row < kGlyphHeight; ++row)
      for (int col = 0; col < kGlyphWidth; ++col)
        if (glyphPixel(text[i], col, row))
          addRect(gx + col * scale, y + row * scale, gx + (col + 1) * scale, y + (row + 1) * scale, color);
  }
}

std::string formatPercent(double fraction) {
  const double percent = fraction * 100.0;
  char buffer[32];
  if (std::abs(percent - std::round(percent)) < 0.05)
    std::snprintf(buffer, sizeof buffer, "%.0f%%", std::round(percent) == 0.0 ? 0.0 : percent);
  else
    std::snprintf(buffer, sizeof buffer, "%.1f%%", percent);
  return buffer;
}

void addStrainLegend(OverlayBuilder& overlay, int width, int height, double strainMin, double strainMax) {
  const int s = legendScale(height);
  const float margin = 10.0f * s, pad = 6.0f * s, barWidth = 10.0f * s, gap = 5.0f * s;
  const float barHeight = std::max(40.0f, 0.40f * height);
  constexpr int kTicks = 5;
  int labelWidth = 0;
  for (int i = 0; i < kTicks; ++i)
    labelWidth = std::max(labelWidth, textWidth(formatPercent(strainMin + (strainMax - strainMin) * i / (kTicks - 1)), s));
  const std::string title = "STRETCH";
  const float contentWidth = std::max(barWidth + gap + labelWidth, static_cast<float>(textWidth(title, s)));
  const float titleHeight = textHeight(s) + 6.0f * s;
  const float x1 = width - margin, x0 = x1 - contentWidth - 2 * pad;
  const float y0 = margin, y1 = y0 + 2 * pad + titleHeight + barHeight + textHeight(s);

  overlay.addRect(x0, y0, x1, y1, {1.0f, 1.0f, 1.0f, 0.78f});
  const Eigen::Vector4f ink{0.13f, 0.14f, 0.16f, 1.0f};
  overlay.addText(x0 + pad, y0 + pad, title, s, ink);

  // The bar: maximum at the top, one gradient quad per ramp segment so it matches the shader exactly.
  const float bx0 = x0 + pad, bx1 = bx0 + barWidth;
  const float by0 = y0 + pad + titleHeight + 0.5f * textHeight(s), by1 = by0 + barHeight;
  const auto& ramp = strainRamp();
  const int segments = static_cast<int>(ramp.size()) - 1;
  for (int i = 0; i < segments; ++i) {
    const float top = by1 - barHeight * (i + 1) / segments, bottom = by1 - barHeight * i / segments;
    overlay.addVerticalGradient(bx0, top, bx1, bottom, opaque(ramp[i + 1]), opaque(ramp[i]));
  }
  const float line = static_cast<float>(s);
  overlay.addRect(bx0 - line, by0 - line, bx1 + line, by0, ink);
  overlay.addRect(bx0 - line, by1, bx1 + line, by1 + line, ink);
  overlay.addRect(bx0 - line, by0, bx0, by1, ink);
  overlay.addRect(bx1, by0, bx1 + line, by1, ink);
  for (int i = 0; i < kTicks; ++i) {
    const float y = by1 - barHeight * i / (kTicks - 1);
    overlay.addRect(bx1, y - 0.5f * line, bx1 + 3.0f * line, y + 0.5f * line, ink);
    const std::string label = formatPercent(strainMin + (strainMax - strainMin) * i / (kTicks - 1));
    overlay.addText(bx1 + gap, std::round(y - 0.5f * textHeight(s)), label, s, ink);
  }
}

void addCornerNote(OverlayBuilder& overlay, int width, int height, std::string_view text) {
  const int s = legendScale(height);
  const float margin = 10.0f * s, pad = 5.0f * s;
  const float x1 = width - margin, x0 = x1 - textWidth(text, s) - 2 * pad;
  overlay.addRect(x0, margin, x1, margin + textHeight(s) + 2 * pad, {1.0f, 1.0f, 1.0f, 0.78f});
  overlay.addText(x0 + pad, margin + pad, text, s, {0.13f, 0.14f, 0.16f, 1.0f});
}

}  // namespace drape::render
