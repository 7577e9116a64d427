#pragma once
// The one renderer of Drape: draws a Snapshot into whatever OpenGL 3.3 core context is current (an EGL or
// OSMesa offscreen context, or Qt's QOpenGLWidget). It computes nothing physical: strain, domains and
// contacts come precomputed in the snapshot.
#include <memory>

#include "drape/render/camera.h"
#include "drape/render/gl_loader.h"
#include "drape/render/render_options.h"
#include "drape/sim/snapshot.h"

namespace drape::render {

class Renderer {
 public:
  // Loads the GL entry points through getProcAddress, compiles the shaders and creates buffers in the
  // context current on this thread. Throws std::runtime_error (GL version too old, shader error).
  explicit Renderer(const GlProcLoader& getProcAddress);
  // Frees GL objects: the context that was current at construction must be current again.
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Copies the snapshot's geometry and per-element attributes into GPU buffers.
  void upload(const Snapshot& snapshot);
  // Draws the last uploaded snapshot into the framebuffer bound now (its full options.width x height),
  // rendering multisampled internally and resolving into it.
  void draw(const Camera& camera, const RenderOptions& options);
  // upload() then draw().
  void draw(const Snapshot& snapshot, const Camera& camera, const RenderOptions& options);

  // "llvmpipe (LLVM 15.0.6, 256 bits)" etc.: the GL_RENDERER string of the context.
  const char* glRendererName() const;
  // Strain scale (fractions) actually used by the last draw in strain mode.
  double lastStrainMin() const;
  double lastStrainMax() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace drape::render
