#pragma once
// How a host hands its OpenGL entry points to the renderer: a function returning the address of a named
// GL function in the host's current context (eglGetProcAddress, OSMesaGetProcAddress,
// QOpenGLContext::getProcAddress). Null when the function is unavailable.
#include <functional>

namespace drape::render {

using GlProcLoader = std::function<void*(const char* name)>;

}  // namespace drape::render
