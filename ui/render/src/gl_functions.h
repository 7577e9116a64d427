#pragma once
// The OpenGL 3.3 core entry points the renderer uses, loaded through a per-host getProcAddress callback.
// Every host (EGL, OSMesa, Qt's GLX or EGL context) resolves the functions of its own current context, so
// the same renderer code runs in all of them without relying on GLVND dispatch (OSMesa is not GLVND).
// Private to drape_render: no public header includes <GL/glcorearb.h>.
#include <GL/glcorearb.h>

#include "drape/render/gl_loader.h"

namespace drape::render {

// X(return type, name, parameter list)
#define DRAPE_GL_FUNCTIONS(X)                                                                           \
  X(void, glActiveTexture, (GLenum))                                                                   \
  X(void, glAttachShader, (GLuint, GLuint))                                                            \
  X(void, glBindBuffer, (GLenum, GLuint))                                                              \
  X(void, glBindFramebuffer, (GLenum, GLuint))                                                         \
  X(void, glBindRenderbuffer, (GLenum, GLuint))                                                        \
  X(void, glBindTexture, (GLenum, GLuint))                                                             \
  X(void, glBindVertexArray, (GLuint))                                                                 \
  X(void, glBlendFuncSeparate, (GLenum, GLenum, GLenum, GLenum))                                       \
  X(void, glBlitFramebuffer, (GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLint, GLbitfield, GLenum)) \
  X(void, glBufferData, (GLenum, GLsizeiptr, const void*, GLenum))                                     \
  X(GLenum, glCheckFramebufferStatus, (GLenum))                                                        \
  X(void, glClear, (GLbitfield))                                                                       \
  X(void, glClearColor, (GLfloat, GLfloat, GLfloat, GLfloat))                                          \
  X(void, glClearDepth, (GLdouble))                                                                    \
  X(void, glCompileShader, (GLuint))                                                                   \
  X(GLuint, glCreateProgram, ())                                                                       \
  X(GLuint, glCreateShader, (GLenum))                                                                  \
  X(void, glDeleteBuffers, (GLsizei, const GLuint*))                                                   \
  X(void, glDeleteFramebuffers, (GLsizei, const GLuint*))                                              \
  X(void, glDeleteProgram, (GLuint))                                                                   \
  X(void, glDeleteRenderbuffers, (GLsizei, const GLuint*))                                             \
  X(void, glDeleteShader, (GLuint))                                                                    \
  X(void, glDeleteTextures, (GLsizei, const GLuint*))                                                  \
  X(void, glDeleteVertexArrays, (GLsizei, const GLuint*))                                              \
  X(void, glDepthFunc, (GLenum))                                                                       \
  X(void, glDepthMask, (GLboolean))                                                                    \
  X(void, glDisable, (GLenum))                                                                         \
  X(void, glDrawArrays, (GLenum, GLint, GLsizei))                                                      \
  X(void, glDrawElements, (GLenum, GLsizei, GLenum, const void*))                                      \
  X(void, glEnable, (GLenum))                                                                          \
  X(void, glEnableVertexAttribArray, (GLuint))                                                         \
  X(void, glFinish, ())                                                                                \
  X(void, glFramebufferRenderbuffer, (GLenum, GLenum, GLenum, GLuint))                                 \
  X(void, glGenBuffers, (GLsizei, GLuint*))                                                            \
  X(void, glGenFramebuffers, (GLsizei, GLuint*))                                                       \
  X(void, glGenRenderbuffers, (GLsizei, GLuint*))                                                      \
  X(void, glGenTextures, (GLsizei, GLuint*))                                                           \
  X(void, glGenerateMipmap, (GLenum))                                                                  \
  X(void, glGenVertexArrays, (GLsizei, GLuint*))                                                       \
  X(GLenum, glGetError, ())                                                                            \
  X(void, glGetIntegerv, (GLenum, GLint*))                                                             \
  X(void, glGetProgramInfoLog, (GLuint, GLsizei, GLsizei*, GLchar*))                                   \
  X(void, glGetProgramiv, (GLuint, GLenum, GLint*))                                                    \
  X(void, glGetShaderInfoLog, (GLuint, GLsizei, GLsizei*, GLchar*))                                    \
  X(void, glGetShaderiv, (GLuint, GLenum, GLint*))                                                     \
  X(const GLubyte*, glGetString, (GLenum))                                                             \
  X(GLint, glGetUniformLocation, (GLuint, const GLchar*))                                              \
  X(void, glLinkProgram, (GLuint))                                                                     \
  X(void, glPixelStorei, (GLenum, GLint))                                                              \
  X(void, glPolygonOffset, (GLfloat, GLfloat))                                                         \
  X(void, glReadBuffer, (GLenum))                                                                      \
  X(void, glReadPixels, (GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void*))                       \
  X(void, glRenderbufferStorage, (GLenum, GLenum, GLsizei, GLsizei))                                   \
  X(void, glRenderbufferStorageMultisample, (GLenum, GLsizei, GLenum, GLsizei, GLsizei))               \
  X(void, glShaderSource, (GLuint, GLsizei, const GLchar* const*, const GLint*))                       \
  X(void, glTexImage2D, (GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void*))  \
  X(void, glTexParameteri, (GLenum, GLenum, GLint))                                                    \
  X(void, glUniform1f, (GLint, GLfloat))                                                               \
  X(void, glUniform1i, (GLint, GLint))                                                                 \
  X(void, glUniform2f, (GLint, GLfloat, GLfloat))                                                      \
  X(void, glUniform3f, (GLint, GLfloat, GLfloat, GLfloat))                                             \
  X(void, glUniform3fv, (GLint, GLsizei, const GLfloat*))                                              \
  X(void, glUniform4f, (GLint, GLfloat, GLfloat, GLfloat, GLfloat))                                              \
  X(void, glUniformMatrix3fv, (GLint, GLsizei, GLboolean, const GLfloat*))                             \
  X(void, glUniformMatrix4fv, (GLint, GLsizei, GLboolean, const GLfloat*))                             \
  X(void, glUseProgram, (GLuint))                                                                      \
  X(void, glVertexAttribPointer, (GLuint, GLint, GLenum, GLboolean, GLsizei, const void*))             \
  X(void, glViewport, (GLint, GLint, GLsizei, GLsizei))

// One table per context. Members carry the GL names: gl.glClear(...).
struct GlFunctions {
#define DRAPE_GL_MEMBER(ret, name, params) ret(APIENTRY* name) params = nullptr;
  DRAPE_GL_FUNCTIONS(DRAPE_GL_MEMBER)
#undef DRAPE_GL_MEMBER

  // Resolves every entry; throws std::runtime_error naming the first function the context lacks.
  void load(const GlProcLoader& getProcAddress);
};

}  // namespace drape::render
