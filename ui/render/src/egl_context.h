#pragma once
// EGL on Mesa's surfaceless platform: an OpenGL 3.3 core context with no window and no display server.
#include <string>

#include "drape/render/gl_loader.h"

namespace drape::render {

class EglContext {
 public:
  // Creates the context and makes it current. Throws std::runtime_error naming the step that failed.
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  void makeCurrent();
  GlProcLoader procLoader() const;

 private:
  void release();
  void* m_display = nullptr;
  void* m_context = nullptr;
};

}  // namespace drape::render
