#include "drape/render/headless.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "bitmap_font.h"
#include "drape/render/renderer.h"

namespace drape::render {

struct OffscreenRenderer::Impl {
  OffscreenContext context;
  Renderer renderer;
  explicit Impl(GlBackend backend) : context(backend), renderer(context.procLoader()) {}
};

OffscreenRenderer::OffscreenRenderer(GlBackend backend) : m_impl(std::make_unique<Impl>(backend)) {}
OffscreenRenderer::~OffscreenRenderer() { m_impl->context.makeCurrent(); }

void OffscreenRenderer::upload(const Snapshot& snapshot) {
  m_impl->context.makeCurrent();
  m_impl->renderer.upload(snapshot);
}

Image OffscreenRenderer::render(const Camera& camera, const RenderOptions& options) {
  m_impl->context.makeCurrent();
  m_impl->context.bindFramebuffer(options.width, options.height);
  m_impl->renderer.draw(camera, options);
  return m_impl->context.readPixels();
}

Image OffscreenRenderer::render(const Snapshot& snapshot, const Camera& camera, const RenderOptions& options) {
  upload(snapshot);
  return render(camera, options);
}

Image OffscreenRenderer::render(const Snapshot& snapshot, ViewPreset preset, const RenderOptions& options) {
  const Camera camera = presetCamera(preset, snapshot.bounds(), double(options.width) / options.height);
  return render(snapshot, camera, options);
}

Image OffscreenRenderer::contactSheet(const Snapshot& snapshot, const RenderOptions& options, bool labels) {
  upload(snapshot);
  constexpr int kColumns = 3, kRows = 2;
  const int w = options.width, h = options.height;
  Image sheet(w * kColumns, h * kRows);
  const auto bg = options.background;
  auto byte = [](float v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  sheet.fill(byte(bg.x()), byte(bg.y()), byte(bg.z()));
  const int scale = std::clamp(h / 180, 1, 4);
  const std::array<std::uint8_t, 3> ink{40, 44, 52};
  const BoundingBox bounds = snapshot.bounds();
  int tile = 0;
  for (ViewPreset preset : kAllViewPresets) {
    const Image image = render(presetCamera(preset, bounds, double(w) / h), options);
    const int x = (tile % kColumns) * w, y = (tile / kColumns) * h;
    sheet.blit(image, x, y);
    if (labels) drawText(sheet, x + 6 * scale, y + 6 * scale, viewPresetName(preset), scale, ink);
    ++tile;
  }
  if (labels) {
    const int x = (tile % kColumns) * w + 6 * scale, y = (tile / kColumns) * h + 6 * scale;
    drawText(sheet, x, y, std::string("MODE: ") + std::string(displayModeName(options.mode)), scale, ink);
    drawText(sheet, x, y + 12 * scale, std::string("STAGE: ") + stageName(snapshot.stage), scale, ink);
    const std::string count = snapshot.triangles.rows() > 0
                                  ? std::to_string(snapshot.triangles.rows()) + " TRIANGLES"
                                  : std::to_string(snapshot.avatar.triangleCount()) + " BODY TRIANGLES";
    drawText(sheet, x, y + 24 * scale, count, scale, ink);
  }
  // Thin separators between the tiles.
  for (int c = 1; c < kColumns; ++c)
    for (int yy = 0; yy < sheet.height; ++yy) {
      std::uint8_t* p = sheet.at(c * w, yy);
      p[0] = p[1] = p[2] = 200;
    }
  for (int xx = 0; xx < sheet.width; ++xx) {
    std::uint8_t* p = sheet.at(xx, h);
    p[0] = p[1] = p[2] = 200;
  }
  return sheet;
}

std::string OffscreenRenderer::backendName() const { return m_impl->context.backendName(); }
std::string OffscreenRenderer::glRendererName() const { return m_impl->renderer.glRendererName(); }

Image renderSnapshot(const Snapshot& snapshot, const Camera& camera, const RenderOptions& options) {
  OffscreenRenderer renderer;
  return renderer.render(snapshot, camera, options);
}

Image renderSnapshot(const Snapshot& snapshot, ViewPreset preset, const RenderOptions& options) {
  OffscreenRenderer renderer;
  return renderer.render(snapshot, preset, options);
}

Image contactSheet(const Snapshot& snapshot, const RenderOptions& options, bool labels) {
  OffscreenRenderer renderer;
  return renderer.contactSheet(snapshot, options, labels);
}

}  // namespace drape::render
