#include "osmesa_context.h"

#include <GL/osmesa.h>
#include <dlfcn.h>

#include <stdexcept>
#include <string>
#include <type_traits>

namespace drape::render {

struct OsMesaContext::Api {
  OSMesaContext (*createContextAttribs)(const int*, OSMesaContext) = nullptr;
  GLboolean (*makeCurrent)(OSMesaContext, void*, GLenum, GLsizei, GLsizei) = nullptr;
  void (*destroyContext)(OSMesaContext) = nullptr;
  OSMESAproc (*getProcAddress)(const char*) = nullptr;
};

namespace {
constexpr int kBufferSize = 16;
}

OsMesaContext::OsMesaContext() : m_api(std::make_unique<Api>()) {
  for (const char* name : {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"}) {
    m_library = dlopen(name, RTLD_NOW | RTLD_LOCAL);
    if (m_library) break;
  }
  if (!m_library) throw std::runtime_error("libOSMesa is not installed (Debian package libosmesa6)");
  auto load = [&](auto& fn, const char* name) {
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(m_library, name));
    if (!fn) {
      dlclose(m_library);
      m_library = nullptr;
      throw std::runtime_error(std::string("libOSMesa lacks ") + name);
    }
  };
  load(m_api->createContextAttribs, "OSMesaCreateContextAttribs");
  load(m_api->makeCurrent, "OSMesaMakeCurrent");
  load(m_api->destroyContext, "OSMesaDestroyContext");
  load(m_api->getProcAddress, "OSMesaGetProcAddress");
  const int attributes[] = {OSMESA_FORMAT,       OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION,
                            3,                   0};
  m_context = m_api->createContextAttribs(attributes, nullptr);
  if (!m_context) {
    dlclose(m_library);
    m_library = nullptr;
    throw std::runtime_error("OSMesaCreateContextAttribs gave no OpenGL 3.3 core context");
  }
  m_buffer.assign(kBufferSize * kBufferSize * 4, 0);
  makeCurrent();
}

OsMesaContext::~OsMesaContext() {
  if (m_context) m_api->destroyContext(static_cast<OSMesaContext>(m_context));
  // The library stays loaded: Mesa keeps thread-local state that must outlive dlclose.
}

void OsMesaContext::makeCurrent() {
  if (!m_api->makeCurrent(static_cast<OSMesaContext>(m_context), m_buffer.data(), GL_UNSIGNED_BYTE, kBufferSize,
                          kBufferSize))
    throw std::runtime_error("OSMesaMakeCurrent failed");
}

GlProcLoader OsMesaContext::procLoader() const {
  auto getProcAddress = m_api->getProcAddress;
  return [getProcAddress](const char* name) { return reinterpret_cast<void*>(getProcAddress(name)); };
}

}  // namespace drape::render
