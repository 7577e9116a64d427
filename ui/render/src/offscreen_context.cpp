#include "drape/render/offscreen_context.h"

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include "egl_context.h"
#include "gl_functions.h"
#include "osmesa_context.h"

namespace drape::render {

struct OffscreenContext::Impl {
  std::unique_ptr<EglContext> egl;
  std::unique_ptr<OsMesaContext> osmesa;
  GlBackend backend = GlBackend::Auto;
  GlFunctions gl;
  GLuint fbo = 0, color = 0, depth = 0;
  int width = 0, height = 0;

  GlProcLoader loader() const { return egl ? egl->procLoader() : osmesa->procLoader(); }
};

namespace {

GlBackend backendFromEnvironment() {
  const char* env = std::getenv("DRAPE_GL_BACKEND");
  if (!env || !*env || std::strcmp(env, "auto") == 0) return GlBackend::Auto;
  if (std::strcmp(env, "egl") == 0) return GlBackend::Egl;
  if (std::strcmp(env, "osmesa") == 0) return GlBackend::OsMesa;
  throw std::runtime_error(std::string("DRAPE_GL_BACKEND='") + env + "' is not one of egl, osmesa, auto");
}

}  // namespace

OffscreenContext::OffscreenContext(GlBackend backend) : m_impl(std::make_unique<Impl>()) {
  if (backend == GlBackend::Auto) backend = backendFromEnvironment();
  std::string errors;
  if (backend == GlBackend::Auto || backend == GlBackend::Egl) {
    try {
      m_impl->egl = std::make_unique<EglContext>();
      m_impl->backend = GlBackend::Egl;
    } catch (const std::exception& e) {
      errors += std::string("EGL: ") + e.what();
    }
  }
  if (!m_impl->egl && (backend == GlBackend::Auto || backend == GlBackend::OsMesa)) {
    try {
      m_impl->osmesa = std::make_unique<OsMesaContext>();
      m_impl->backend = GlBackend::OsMesa;
    } catch (const std::exception& e) {
      errors += std::string(errors.empty() ? "" : "; ") + "OSMesa: " + e.what();
    }
  }
  if (!m_impl->egl && !m_impl->osmesa)
    throw std::runtime_error("no OpenGL 3.3 context could be created (" + errors + ")");
  m_impl->gl.load(m_impl->loader());
}

OffscreenContext::~OffscreenContext() {
  Impl& c = *m_impl;
  if (c.fbo) {
    makeCurrent();
    c.gl.glDeleteFramebuffers(1, &c.fbo);
    const GLuint renderbuffers[] = {c.color, c.depth};
    c.gl.glDeleteRenderbuffers(2, renderbuffers);
  }
}

GlBackend OffscreenContext::backend() const { return m_impl->backend; }
std::string OffscreenContext::backendName() const { return m_impl->egl ? "egl" : "osmesa"; }
GlProcLoader OffscreenContext::procLoader() const { return m_impl->loader(); }

void OffscreenContext::makeCurrent() {
  if (m_impl->egl)
    m_impl->egl->makeCurrent();
  else
    m_impl->osmesa->makeCurrent();
}

void OffscreenContext::bindFramebuffer(int width, int height) {
  Impl& c = *m_impl;
  const GlFunctions& gl = c.gl;
  if (!c.fbo) {
    gl.glGenFramebuffers(1, &c.fbo);
    gl.glGenRenderbuffers(1, &c.color);
    gl.glGenRenderbuffers(1, &c.depth);
  }
  if (width != c.width || height != c.height) {
    gl.glBindRenderbuffer(GL_RENDERBUFFER, c.color);
    gl.glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    gl.glBindRenderbuffer(GL_RENDERBUFFER, c.depth);
    gl.glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    gl.glBindRenderbuffer(GL_RENDERBUFFER, 0);
    gl.glBindFramebuffer(GL_FRAMEBUFFER, c.fbo);
    gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, c.color);
    gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, c.depth);
    if (gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("offscreen context: cannot create a " + std::to_string(width) + "x" +
                               std::to_string(height) + " framebuffer");
    c.width = width, c.height = height;
  }
  gl.glBindFramebuffer(GL_FRAMEBUFFER, c.fbo);
  gl.glViewport(0, 0, width, height);
}

Image OffscreenContext::readPixels() {
  Impl& c = *m_impl;
  const GlFunctions& gl = c.gl;
  Image image(c.width, c.height);
  if (image.empty()) return image;
  std::vector<std::uint8_t> bottomUp(image.pixels.size());
  gl.glBindFramebuffer(GL_READ_FRAMEBUFFER, c.fbo);
  gl.glReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.glPixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.glReadPixels(0, 0, c.width, c.height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
  const size_t row = static_cast<size_t>(c.width) * 4;
  for (int y = 0; y < c.height; ++y)
    std::memcpy(image.at(0, y), bottomUp.data() + (c.height - 1 - y) * row, row);
  return image;
}

}  // namespace drape::render
