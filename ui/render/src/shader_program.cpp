#include "shader_program.h"

#include <stdexcept>
#include <vector>

namespace drape::render {
namespace {

GLuint compile(const GlFunctions& gl, GLenum type, std::string_view file) {
  const char* source = embeddedShader(file);
  if (!source) throw std::runtime_error("renderer: shader '" + std::string(file) + "' is not embedded");
  GLuint shader = gl.glCreateShader(type);
  gl.glShaderSource(shader, 1, &source, nullptr);
  gl.glCompileShader(shader);
  GLint ok = 0;
  gl.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    gl.glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(std::max(length, 1));
    gl.glGetShaderInfoLog(shader, length, nullptr, log.data());
    gl.glDeleteShader(shader);
    throw std::runtime_error("renderer: shader '" + std::string(file) + "' does not compile: " + log.data());
  }
  return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(const GlFunctions& gl, std::string_view vertexFile, std::string_view fragmentFile)
    : m_gl(gl) {
  GLuint vs = compile(gl, GL_VERTEX_SHADER, vertexFile);
  GLuint fs = 0;
  try {
    fs = compile(gl, GL_FRAGMENT_SHADER, fragmentFile);
  } catch (...) {
    gl.glDeleteShader(vs);
    throw;
  }
  m_program = gl.glCreateProgram();
  gl.glAttachShader(m_program, vs);
  gl.glAttachShader(m_program, fs);
  gl.glLinkProgram(m_program);
  gl.glDeleteShader(vs);
  gl.glDeleteShader(fs);
  GLint ok = 0;
  gl.glGetProgramiv(m_program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    gl.glGetProgramiv(m_program, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(std::max(length, 1));
    gl.glGetProgramInfoLog(m_program, length, nullptr, log.data());
    gl.glDeleteProgram(m_program);
    throw std::runtime_error("renderer: program '" + std::string(vertexFile) + "' + '" + std::string(fragmentFile) +
                             "' does not link: " + log.data());
  }
}

ShaderProgram::~ShaderProgram() {
  if (m_program) m_gl.glDeleteProgram(m_program);
}

GLint ShaderProgram::uniform(const char* name) {
  auto it = m_uniforms.find(name);
  if (it != m_uniforms.end()) return it->second;
  const GLint location = m_gl.glGetUniformLocation(m_program, name);
  m_uniforms.emplace(name, location);
  return location;
}

}  // namespace drape::render
