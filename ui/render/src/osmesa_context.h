#pragma once
// OSMesa (Mesa's off-screen software renderer) loaded with dlopen, so drape_render neither links it nor
// lets its gl* symbols clash with GLVND's. An OpenGL 3.3 core context drawing into a small host buffer;
// the renderer itself draws into a framebuffer object.
#include <memory>
#include <vector>

#include "drape/render/gl_loader.h"

namespace drape::render {

class OsMesaContext {
 public:
  // Throws std::runtime_error when libOSMesa cannot be loaded or gives no 3.3 core context.
  OsMesaContext();
  ~OsMesaContext();
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  void makeCurrent();
  GlProcLoader procLoader() const;

 private:
  struct Api;
  std::unique_ptr<Api> m_api;
  void* m_library = nullptr;
  void* m_context = nullptr;
  std::vector<unsigned char> m_buffer;  // 16 x 16 RGBA: OSMesaMakeCurrent needs one
};

}  // namespace drape::render
