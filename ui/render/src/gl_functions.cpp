#include "gl_functions.h"

#include <stdexcept>
#include <string>

namespace drape::render {

void GlFunctions::load(const GlProcLoader& getProcAddress) {
  if (!getProcAddress) throw std::runtime_error("OpenGL: no getProcAddress function given");
#define DRAPE_GL_LOAD(ret, name, params)                                                             \
  name = reinterpret_cast<ret(APIENTRY*) params>(getProcAddress(#name));                            \
  if (!name) throw std::runtime_error("OpenGL: the current context does not provide " #name);
  DRAPE_GL_FUNCTIONS(DRAPE_GL_LOAD)
#undef DRAPE_GL_LOAD
}

}  // namespace drape::render
