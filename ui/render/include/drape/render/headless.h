#pragma once
// One call per image for the CLI: create an offscreen context, draw, read back. No window, no Qt.
#include <memory>
#include <string>

#include "drape/render/camera.h"
#include "drape/render/image.h"
#include "drape/render/offscreen_context.h"
#include "drape/render/render_options.h"
#include "drape/sim/snapshot.h"

namespace drape::render {

// An offscreen context plus a renderer, kept for many images (tests, benchmarks, --view all).
class OffscreenRenderer {
 public:
  explicit OffscreenRenderer(GlBackend backend = GlBackend::Auto);
  ~OffscreenRenderer();

  // The snapshot is uploaded on every call; use upload() + render(camera, options) to draw it repeatedly.
  Image render(const Snapshot& snapshot, const Camera& camera, const RenderOptions& options);
  Image render(const Snapshot& snapshot, ViewPreset preset, const RenderOptions& options);
  void upload(const Snapshot& snapshot);
  Image render(const Camera& camera, const RenderOptions& options);

  // All five presets tiled 3 x 2 (each tile options.width x options.height); the sixth tile names the mode.
  // With labels, each tile carries its view name in the top-left corner.
  Image contactSheet(const Snapshot& snapshot, const RenderOptions& options, bool labels = true);

  std::string backendName() const;
  std::string glRendererName() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

// Convenience wrappers creating a context for the one call. Throw std::runtime_error when no GL context
// can be created ("no OpenGL context: EGL: ...; OSMesa: ...").
Image renderSnapshot(const Snapshot& snapshot, const Camera& camera, const RenderOptions& options);
Image renderSnapshot(const Snapshot& snapshot, ViewPreset preset, const RenderOptions& options);
Image contactSheet(const Snapshot& snapshot, const RenderOptions& options, bool labels = true);

}  // namespace drape::render
