#pragma once
// A headless OpenGL 3.3 core context with no window and no display server: EGL on Mesa's surfaceless
// platform, or OSMesa as a fallback. The environment variable DRAPE_GL_BACKEND=egl|osmesa forces one.
#include <memory>
#include <string>

#include "drape/render/gl_loader.h"
#include "drape/render/image.h"

namespace drape::render {

enum class GlBackend { Auto, Egl, OsMesa };

class OffscreenContext {
 public:
  // Creates the context and makes it current on this thread. Auto tries DRAPE_GL_BACKEND if set, else EGL
  // then OSMesa. Throws std::runtime_error with one line naming what was tried and why each failed.
  explicit OffscreenContext(GlBackend backend = GlBackend::Auto);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  GlBackend backend() const;
  std::string backendName() const;  // "egl" or "osmesa"
  GlProcLoader procLoader() const;
  void makeCurrent();

  // Binds a width x height RGBA8 framebuffer (with depth) as the draw target, resizing it as needed.
  void bindFramebuffer(int width, int height);
  // Reads that framebuffer back, rows top to bottom.
  Image readPixels();

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace drape::render
