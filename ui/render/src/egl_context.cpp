#include "egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <mutex>
#include <stdexcept>
#include <string>

namespace drape::render {
namespace {

// eglTerminate is not reference counted and Mesa returns one EGLDisplay per platform, so contexts that
// coexist share the display and the last one terminates it.
std::mutex g_displayMutex;
int g_displayUsers = 0;

std::string eglErrorText(const char* step) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(eglGetError()));
  return std::string(step) + " failed (EGL error " + code + ")";
}

}  // namespace

EglContext::EglContext() {
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) throw std::runtime_error("eglGetPlatformDisplayEXT is not available");
  EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) throw std::runtime_error("no EGL display on the Mesa surfaceless platform");
  {
    std::lock_guard<std::mutex> lock(g_displayMutex);
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) throw std::runtime_error(eglErrorText("eglInitialize"));
    ++g_displayUsers;
  }
  m_display = display;
  try {
    if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(eglErrorText("eglBindAPI(EGL_OPENGL_API)"));
    const EGLint configAttributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                       EGL_RED_SIZE,     8,               EGL_GREEN_SIZE,      8,
                                       EGL_BLUE_SIZE,    8,               EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &count) || count < 1)
      config = nullptr;  // EGL_KHR_no_config_context: Mesa accepts a context without a config
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT) throw std::runtime_error(eglErrorText("eglCreateContext (OpenGL 3.3 core)"));
    m_context = context;
    makeCurrent();
  } catch (...) {
    release();
    throw;
  }
}

EglContext::~EglContext() { release(); }

void EglContext::release() {
  if (!m_display) return;
  EGLDisplay display = static_cast<EGLDisplay>(m_display);
  if (m_context) {
    if (eglGetCurrentContext() == static_cast<EGLContext>(m_context))
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, static_cast<EGLContext>(m_context));
    m_context = nullptr;
  }
  std::lock_guard<std::mutex> lock(g_displayMutex);
  if (--g_displayUsers == 0) eglTerminate(display);
  m_display = nullptr;
}

void EglContext::makeCurrent() {
  if (!eglMakeCurrent(static_cast<EGLDisplay>(m_display), EGL_NO_SURFACE, EGL_NO_SURFACE,
                      static_cast<EGLContext>(m_context)))
    throw std::runtime_error(eglErrorText("eglMakeCurrent (surfaceless)"));
}

GlProcLoader EglContext::procLoader() const {
  return [](const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); };
}

}  // namespace drape::render
