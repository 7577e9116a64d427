#include "drape/render/renderer.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "gl_functions.h"
#include "mesh_buffers.h"
#include "overlay.h"
#include "drape/render/palette.h"
#include "shader_program.h"

namespace drape::render {
namespace {

enum ShaderMode { kShaded = 0, kWireframe = 1, kStrain = 2, kDomains = 3, kContacts = 4, kAvatar = 5, kPrint = 6 };

ShaderMode shaderMode(DisplayMode mode) {
  switch (mode) {
    case DisplayMode::Shaded: return kShaded;
    case DisplayMode::Wireframe: return kWireframe;
    case DisplayMode::Strain: return kStrain;
    case DisplayMode::Domains: return kDomains;
    case DisplayMode::Contacts: return kContacts;
    case DisplayMode::Print: return kPrint;
  }
  return kShaded;
}

void setVec3(const GlFunctions& gl, GLint location, const Eigen::Vector3f& v) {
  gl.glUniform3f(location, v.x(), v.y(), v.z());
}
void setVec3(const GlFunctions& gl, GLint location, const Eigen::Vector3d& v) {
  setVec3(gl, location, Eigen::Vector3f(v.cast<float>()));
}

}  // namespace

struct Renderer::Impl {
  GlFunctions gl;
  std::unique_ptr<ShaderProgram> meshProgram, groundProgram, backgroundProgram, overlayProgram;
  GLuint garmentVao = 0, garmentVbo = 0;
  GLsizei garmentVertexCount = 0;
  GLuint avatarVao = 0, avatarVbo = 0, avatarEbo = 0;
  GLsizei avatarIndexCount = 0;
  GLuint groundVao = 0, groundVbo = 0;
  GLuint emptyVao = 0;
  GLuint overlayVao = 0, overlayVbo = 0;
  GLuint msFbo = 0, msColor = 0, msDepth = 0;
  int fboWidth = 0, fboHeight = 0, fboSamples = -1;
  GLint maxSamples = 0;
  BoundingBox bounds;
  bool hasStrain = false;
  double strainMaximum = 0.0;
  float avatarInset = 0.0f;  // metres, Snapshot::contactThickness
  double lastStrainMin = 0.0, lastStrainMax = 0.0;
  std::string rendererName;
  GLuint printTexture = 0;
  std::shared_ptr<const Image> printUploaded;  // the image in printTexture, held so that it stays the same image

  void createBuffers();
  void ensureFramebuffer(int width, int height, int samples);
  void drawBackground(const RenderOptions& options);
  void drawGround(const Eigen::Matrix4f& viewProjection, const Camera& camera, const RenderOptions& options);
  void drawMeshes(const Eigen::Matrix4f& viewProjection, const Camera& camera, const RenderOptions& options);
  void drawOverlay(const RenderOptions& options);
  // Binds the print of options to texture unit 0, uploading it (with mipmaps, repeating) when it is a new image.
  bool bindPrint(const RenderOptions& options);
};

Renderer::Renderer(const GlProcLoader& getProcAddress) : m_impl(std::make_unique<Impl>()) {
  Impl& r = *m_impl;
  r.gl.load(getProcAddress);
  const char* version = reinterpret_cast<const char*>(r.gl.glGetString(GL_VERSION));
  const char* name = reinterpret_cast<const char*>(r.gl.glGetString(GL_RENDERER));
  int major = 0, minor = 0;
  if (!version || std::sscanf(version, "%d.%d", &major, &minor) != 2 || major * 10 + minor < 33)
    throw std::runtime_error(std::string("renderer: OpenGL 3.3 core is required, the context provides ") +
                             (version ? version : "no version string"));
  r.rendererName = name ? name : "unknown";
  r.meshProgram = std::make_unique<ShaderProgram>(r.gl, "mesh.vert", "mesh.frag");
  r.groundProgram = std::make_unique<ShaderProgram>(r.gl, "ground.vert", "ground.frag");
  r.backgroundProgram = std::make_unique<ShaderProgram>(r.gl, "background.vert", "background.frag");
  r.overlayProgram = std::make_unique<ShaderProgram>(r.gl, "overlay.vert", "overlay.frag");
  r.gl.glGetIntegerv(GL_MAX_SAMPLES, &r.maxSamples);
  r.createBuffers();
}

Renderer::~Renderer() {
  Impl& r = *m_impl;
  const GlFunctions& gl = r.gl;
  const GLuint buffers[] = {r.garmentVbo, r.avatarVbo, r.avatarEbo, r.groundVbo, r.overlayVbo};
  gl.glDeleteBuffers(5, buffers);
  const GLuint arrays[] = {r.garmentVao, r.avatarVao, r.groundVao, r.emptyVao, r.overlayVao};
  gl.glDeleteVertexArrays(5, arrays);
  if (r.msFbo) gl.glDeleteFramebuffers(1, &r.msFbo);
  if (r.printTexture) gl.glDeleteTextures(1, &r.printTexture);
  const GLuint renderbuffers[] = {r.msColor, r.msDepth};
  gl.glDeleteRenderbuffers(2, renderbuffers);
  r.meshProgram.reset();
  r.groundProgram.reset();
  r.backgroundProgram.reset();
  r.overlayProgram.reset();
}

void Renderer::Impl::createBuffers() {
  gl.glGenVertexArrays(1, &garmentVao);
  gl.glGenBuffers(1, &garmentVbo);
  gl.glBindVertexArray(garmentVao);
  gl.glBindBuffer(GL_ARRAY_BUFFER, garmentVbo);
  const GLsizei stride = kGarmentFloats * sizeof(float);
  const int sizes[] = {3, 3, 3, 3, 3, 1, 1, 2};
  size_t offset = 0;
  for (GLuint i = 0; i < 8; ++i) {
    gl.glEnableVertexAttribArray(i);
    gl.glVertexAttribPointer(i, sizes[i], GL_FLOAT, GL_FALSE, stride, reinterpret_cast<const void*>(offset));
    offset += sizes[i] * sizeof(float);
  }

  gl.glGenVertexArrays(1, &avatarVao);
  gl.glGenBuffers(1, &avatarVbo);
  gl.glGenBuffers(1, &avatarEbo);
  gl.glBindVertexArray(avatarVao);
  gl.glBindBuffer(GL_ARRAY_BUFFER, avatarVbo);
  gl.glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, avatarEbo);
  for (GLuint i = 0; i < 2; ++i) {
    gl.glEnableVertexAttribArray(i);
    gl.glVertexAttribPointer(i, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                             reinterpret_cast<const void*>(i * 3 * sizeof(float)));
  }

  gl.glGenVertexArrays(1, &groundVao);
  gl.glGenBuffers(1, &groundVbo);
  gl.glBindVertexArray(groundVao);
  gl.glBindBuffer(GL_ARRAY_BUFFER, groundVbo);
  const float corners[] = {-1, -1, 1, -1, 1, 1, -1, -1, 1, 1, -1, 1};
  gl.glBufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
  gl.glEnableVertexAttribArray(0);
  gl.glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);

  gl.glGenVertexArrays(1, &emptyVao);

  gl.glGenVertexArrays(1, &overlayVao);
  gl.glGenBuffers(1, &overlayVbo);
  gl.glBindVertexArray(overlayVao);
  gl.glBindBuffer(GL_ARRAY_BUFFER, overlayVbo);
  gl.glEnableVertexAttribArray(0);
  gl.glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex), nullptr);
  gl.glEnableVertexAttribArray(1);
  gl.glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex),
                           reinterpret_cast<const void*>(2 * sizeof(float)));
  gl.glBindVertexArray(0);
  gl.glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void Renderer::upload(const Snapshot& snapshot) {
  Impl& r = *m_impl;
  const GarmentVertices garment = buildGarmentVertices(snapshot);
  const AvatarVertices avatar = buildAvatarVertices(snapshot.avatar);
  r.gl.glBindVertexArray(0);
  r.gl.glBindBuffer(GL_ARRAY_BUFFER, r.garmentVbo);
  r.gl.glBufferData(GL_ARRAY_BUFFER, garment.data.size() * sizeof(float), garment.data.data(), GL_STATIC_DRAW);
  r.garmentVertexCount = static_cast<GLsizei>(garment.data.size() / kGarmentFloats);
  r.gl.glBindBuffer(GL_ARRAY_BUFFER, r.avatarVbo);
  r.gl.glBufferData(GL_ARRAY_BUFFER, avatar.data.size() * sizeof(float), avatar.data.data(), GL_STATIC_DRAW);
  r.gl.glBindVertexArray(r.avatarVao);
  r.gl.glBufferData(GL_ELEMENT_ARRAY_BUFFER, avatar.indices.size() * sizeof(unsigned), avatar.indices.data(),
                    GL_STATIC_DRAW);
  r.gl.glBindVertexArray(0);
  r.gl.glBindBuffer(GL_ARRAY_BUFFER, 0);
  r.avatarIndexCount = static_cast<GLsizei>(avatar.indices.size());
  r.hasStrain = garment.hasStrain;
  r.strainMaximum = garment.strainMaximum;
  r.avatarInset = static_cast<float>(snapshot.contactThickness);
  r.bounds = snapshot.bounds();
}

void Renderer::Impl::ensureFramebuffer(int width, int height, int samples) {
  if (width == fboWidth && height == fboHeight && samples == fboSamples && msFbo) return;
  if (!msFbo) {
    gl.glGenFramebuffers(1, &msFbo);
    gl.glGenRenderbuffers(1, &msColor);
    gl.glGenRenderbuffers(1, &msDepth);
  }
  gl.glBindRenderbuffer(GL_RENDERBUFFER, msColor);
  gl.glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
  gl.glBindRenderbuffer(GL_RENDERBUFFER, msDepth);
  gl.glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
  gl.glBindRenderbuffer(GL_RENDERBUFFER, 0);
  gl.glBindFramebuffer(GL_FRAMEBUFFER, msFbo);
  gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msColor);
  gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msDepth);
  const GLenum status = gl.glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("renderer: cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
                             " framebuffer with " + std::to_string(samples) + " samples (status " +
                             std::to_string(status) + ")");
  fboWidth = width, fboHeight = height, fboSamples = samples;
}

void Renderer::draw(const Snapshot& snapshot, const Camera& camera, const RenderOptions& options) {
  upload(snapshot);
  draw(camera, options);
}

void Renderer::draw(const Camera& camera, const RenderOptions& options) {
  Impl& r = *m_impl;
  const GlFunctions& gl = r.gl;
  if (options.width <= 0 || options.height <= 0 || options.width > 16384 || options.height > 16384)
    throw std::invalid_argument("renderer: image size " + std::to_string(options.width) + "x" +
                                std::to_string(options.height) + " is out of range (1..16384)");
  GLint target = 0;
  gl.glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  const int samples = options.msaaSamples <= 1 ? 0 : std::min(options.msaaSamples, std::max(r.maxSamples, 0));
  r.ensureFramebuffer(options.width, options.height, samples);

  gl.glBindFramebuffer(GL_FRAMEBUFFER, r.msFbo);
  gl.glViewport(0, 0, options.width, options.height);
  gl.glDisable(GL_SCISSOR_TEST);
  gl.glDisable(GL_CULL_FACE);
  gl.glDisable(GL_FRAMEBUFFER_SRGB);
  gl.glDisable(GL_STENCIL_TEST);
  gl.glDepthMask(GL_TRUE);
  gl.glClearDepth(1.0);
  gl.glClearColor(0, 0, 0, 1);
  gl.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  const double aspect = double(options.width) / double(options.height);
  const Eigen::Matrix4f viewProjection = camera.projectionMatrix(aspect) * camera.viewMatrix();
  r.drawBackground(options);
  if (options.showGround && !r.bounds.empty()) r.drawGround(viewProjection, camera, options);
  r.drawMeshes(viewProjection, camera, options);
  r.drawOverlay(options);

  gl.glBindVertexArray(0);
  gl.glUseProgram(0);
  gl.glBindFramebuffer(GL_READ_FRAMEBUFFER, r.msFbo);
  gl.glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(target));
  gl.glBlitFramebuffer(0, 0, options.width, options.height, 0, 0, options.width, options.height,
                       GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl.glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target));
}

void Renderer::Impl::drawBackground(const RenderOptions& options) {
  gl.glDisable(GL_DEPTH_TEST);
  gl.glDisable(GL_BLEND);
  backgroundProgram->use();
  setVec3(gl, backgroundProgram->uniform("u_top"), options.background);
  setVec3(gl, backgroundProgram->uniform("u_bottom"), Eigen::Vector3f(options.background * 0.84f));
  gl.glBindVertexArray(emptyVao);
  gl.glDrawArrays(GL_TRIANGLES, 0, 3);
}

void Renderer::Impl::drawGround(const Eigen::Matrix4f& viewProjection, const Camera& camera,
                                const RenderOptions& options) {
  const Eigen::Vector3d size = bounds.size();
  const double maxDim = std::max({size.x(), size.y(), size.z(), 1e-3});
  const Eigen::Vector3d center(bounds.center().x(), bounds.min.y() - 1e-3 * maxDim, bounds.center().z());
  const float extent = static_cast<float>(2.5 * maxDim);
  gl.glEnable(GL_DEPTH_TEST);
  gl.glDepthFunc(GL_LESS);
  gl.glEnable(GL_BLEND);
  gl.glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // alpha stays 1
  groundProgram->use();
  gl.glUniformMatrix4fv(groundProgram->uniform("u_viewProjection"), 1, GL_FALSE, viewProjection.data());
  setVec3(gl, groundProgram->uniform("u_center"), center);
  gl.glUniform1f(groundProgram->uniform("u_extent"), extent);
  gl.glUniform2f(groundProgram->uniform("u_shadowRadius"), float(0.55 * std::max(size.x(), 0.05 * maxDim)),
                 float(0.55 * std::max(size.z(), 0.05 * maxDim)));
  gl.glUniform1f(groundProgram->uniform("u_gridStep"), float(niceCeil(maxDim / 12.0)));
  setVec3(gl, groundProgram->uniform("u_floorColor"), Eigen::Vector3f(options.background * 0.97f));
  setVec3(gl, groundProgram->uniform("u_lineColor"), Eigen::Vector3f(options.background * 0.80f));
  setVec3(gl, groundProgram->uniform("u_eye"), camera.eye);
  gl.glBindVertexArray(groundVao);
  gl.glDrawArrays(GL_TRIANGLES, 0, 6);
  gl.glDisable(GL_BLEND);
}

void Renderer::Impl::drawMeshes(const Eigen::Matrix4f& viewProjection, const Camera& camera,
                                const RenderOptions& options) {
  gl.glEnable(GL_DEPTH_TEST);
  gl.glDepthFunc(GL_LESS);
  gl.glDisable(GL_BLEND);
  ShaderProgram& p = *meshProgram;
  p.use();
  gl.glUniformMatrix4fv(p.uniform("u_viewProjection"), 1, GL_FALSE, viewProjection.data());
  setVec3(gl, p.uniform("u_eye"), camera.eye);
  // Lights follow the camera: key from the upper left, fill from the right, rim from behind.
  const Eigen::Vector3d back = (camera.eye - camera.target).normalized();
  Eigen::Vector3d right = camera.up.cross(back);
  if (right.norm() < 1e-9) right = Eigen::Vector3d::UnitX();
  right.normalize();
  const Eigen::Vector3d up = back.cross(right);
  setVec3(gl, p.uniform("u_keyDir"), Eigen::Vector3d((-0.45 * right + 0.75 * up + 0.55 * back).normalized()));
  setVec3(gl, p.uniform("u_fillDir"), Eigen::Vector3d((0.80 * right + 0.05 * up + 0.45 * back).normalized()));
  setVec3(gl, p.uniform("u_rimDir"), Eigen::Vector3d((0.30 * right + 0.50 * up - 0.80 * back).normalized()));
  setVec3(gl, p.uniform("u_neutralColor"), displayToLinear({0.86f, 0.85f, 0.82f}));
  setVec3(gl, p.uniform("u_avatarColor"), displayToLinear({0.66f, 0.67f, 0.69f}));
  setVec3(gl, p.uniform("u_contactColor"), displayToLinear({1.0f, 0.36f, 0.10f}));
  const auto& ramp = strainRamp();
  gl.glUniform3fv(p.uniform("u_ramp"), static_cast<GLsizei>(ramp.size()), ramp[0].data());
  gl.glUniform1i(p.uniform("u_rampCount"), static_cast<GLint>(ramp.size()));
  lastStrainMin = options.strainMin;
  lastStrainMax = options.strainMax > options.strainMin
                      ? options.strainMax
                      : (strainMaximum > options.strainMin ? options.strainMin + niceCeil(strainMaximum - options.strainMin)
                                                           : options.strainMin + 0.05);
  gl.glUniform2f(p.uniform("u_strainRange"), float(lastStrainMin), float(lastStrainMax));

  if (options.showAvatar && avatarIndexCount > 0) {
    gl.glUniform1i(p.uniform("u_mode"), kAvatar);
    gl.glUniform1i(p.uniform("u_edges"), 0);
    gl.glUniform1f(p.uniform("u_inset"), avatarInset);
    gl.glBindVertexArray(avatarVao);
    gl.glDrawElements(GL_TRIANGLES, avatarIndexCount, GL_UNSIGNED_INT, nullptr);
  }
  if (garmentVertexCount > 0) {
    const bool wire = options.mode == DisplayMode::Wireframe;
    gl.glUniform1i(p.uniform("u_mode"), shaderMode(options.mode));
    gl.glUniform1f(p.uniform("u_inset"), 0.0f);
    const bool print = options.mode == DisplayMode::Print && bindPrint(options);
    gl.glUniform1i(p.uniform("u_hasPrint"), print);
    gl.glUniform1i(p.uniform("u_print"), 0);
    gl.glUniform1f(p.uniform("u_printWidth"), float(options.printWidth > 0.0 ? options.printWidth : 0.25));
    gl.glUniform1f(p.uniform("u_printAspect"),
                   print ? float(options.print->height) / float(options.print->width) : 1.0f);
    gl.glUniform1i(p.uniform("u_edges"), wire || options.wireframeOverlay);
    if (wire)
      gl.glUniform4f(p.uniform("u_edgeColor"), 0.13f, 0.17f, 0.24f, 0.90f);
    else
      gl.glUniform4f(p.uniform("u_edgeColor"), 0.05f, 0.05f, 0.08f, 0.45f);
    gl.glBindVertexArray(garmentVao);
    gl.glDrawArrays(GL_TRIANGLES, 0, garmentVertexCount);
  }
}

bool Renderer::Impl::bindPrint(const RenderOptions& options) {
  const Image* image = options.print.get();
  if (!image || image->empty() || image->pixels.size() != static_cast<size_t>(image->width) * image->height * 4)
    return false;
  if (!printTexture) gl.glGenTextures(1, &printTexture);
  gl.glActiveTexture(GL_TEXTURE0);
  gl.glBindTexture(GL_TEXTURE_2D, printTexture);
  if (options.print != printUploaded) {
    gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image->width, image->height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                    image->pixels.data());
    gl.glGenerateMipmap(GL_TEXTURE_2D);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    printUploaded = options.print;
  }
  return true;
}

void Renderer::Impl::drawOverlay(const RenderOptions& options) {
  OverlayBuilder overlay;
  if (options.mode == DisplayMode::Strain && options.showLegend && garmentVertexCount > 0) {
    if (hasStrain)
      addStrainLegend(overlay, options.width, options.height, lastStrainMin, lastStrainMax);
    else
      addCornerNote(overlay, options.width, options.height, "NO STRAIN DATA");
  }
  if (overlay.empty()) return;
  gl.glDisable(GL_DEPTH_TEST);
  gl.glEnable(GL_BLEND);
  gl.glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // alpha stays 1
  overlayProgram->use();
  gl.glUniform2f(overlayProgram->uniform("u_viewport"), float(options.width), float(options.height));
  gl.glBindVertexArray(overlayVao);
  gl.glBindBuffer(GL_ARRAY_BUFFER, overlayVbo);
  gl.glBufferData(GL_ARRAY_BUFFER, overlay.vertices().size() * sizeof(OverlayVertex), overlay.vertices().data(),
                  GL_STREAM_DRAW);
  gl.glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(overlay.vertices().size()));
  gl.glBindBuffer(GL_ARRAY_BUFFER, 0);
  gl.glDisable(GL_BLEND);
}

const char* Renderer::glRendererName() const { return m_impl->rendererName.c_str(); }
double Renderer::lastStrainMin() const { return m_impl->lastStrainMin; }
double Renderer::lastStrainMax() const { return m_impl->lastStrainMax; }

}  // namespace drape::render
