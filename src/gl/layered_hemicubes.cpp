#include "gl/shooter_hemicubes.h"

#include <epoxy/gl.h>

#include <limits>

#include <fmt/format.h>

#include "gl/gl_context.h"
#include "gl/hemicube_glsl.h"
#include "gl/shader_program.h"
#include "gl/shared_layout.h"
#include "luxel/error.h"

namespace luxel::gl {
namespace {

const char* kShooterVertex = R"(
layout(location = POSITION_LOCATION) in vec3 position;
layout(location = ITEM_LOCATION) in uint item;
layout(std430, binding = SHOOTER_BINDING) readonly buffer Shooters { GpuShooter shooters[]; };
uniform int layer;
uniform float nearPlane, farPlane;
flat out uint vItem;
out vec3 vFromEye;
void main() {
  GpuShooter s = shooters[layer / 5];
  vItem = item;
  vFromEye = position - s.eye.xyz;
  gl_Position = s.ids.y == 0u ? vec4(2.0, 2.0, 2.0, 1.0)  // an empty slot: outside the clip volume
                              : hemicubeClip(position, s.eye.xyz, hemicubeFrame(s.normal.xyz), layer % 5, nearPlane, farPlane);
}
)";

const char* kShooterFragment = R"(
flat in uint vItem;
in vec3 vFromEye;
layout(location = 0) out uint outItem;
layout(location = 1) out float outDistance;
void main() {
  outItem = vItem;
  outDistance = length(vFromEye);
}
)";

}  // namespace

struct ShooterHemicubes::Impl {
  GLuint vao = 0, positions = 0, items = 0, itemLayers = 0, distanceLayers = 0, depth = 0;
  std::vector<GLuint> framebuffers;  // one per layer (hemicube x face)
  GLsizei vertexCount = 0;
  std::unique_ptr<ShaderProgram> program;
  GLint layer = -1;

  ~Impl() {
    if (!framebuffers.empty()) glDeleteFramebuffers(GLsizei(framebuffers.size()), framebuffers.data());
    glDeleteTextures(1, &itemLayers);
    glDeleteTextures(1, &distanceLayers);
    glDeleteRenderbuffers(1, &depth);
    glDeleteBuffers(1, &positions);
    glDeleteBuffers(1, &items);
    glDeleteVertexArrays(1, &vao);
  }
};

uint32_t ShooterHemicubes::itemOfFace(const SurfaceSet& surfaces, uint32_t face) {
  const int32_t twin = surfaces.faces[face].twin;
  return (twin >= 0 && uint32_t(twin) < face ? uint32_t(twin) : face) + 1;
}

ShooterHemicubes::ShooterHemicubes(const SurfaceSet& surfaces, int resolution, int hemicubes, float nearPlane,
                                   float farPlane)
    : impl_(std::make_unique<Impl>()), resolution_(resolution), hemicubes_(hemicubes), near_(nearPlane), far_(farPlane) {
  GLint maxLayers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  if (resolution < 2 || resolution % 2 || resolution > 4096)
    throw Error(fmt::format("hemicube resolution {} must be even, from 2 to 4096", resolution));
  if (hemicubes < 1 || 5 * hemicubes > maxLayers)
    throw Error(fmt::format("{} hemicubes per pass need {} texture layers; this OpenGL has {}", hemicubes,
                            5 * hemicubes, maxLayers));
  if (!(nearPlane > 0.0f && farPlane > nearPlane)) throw Error("hemicube near and far planes must be 0 < near < far");
  Impl& m = *impl_;

  // Each face once: its twin (the other side of a two-sided surface) lies in the same plane.
  std::vector<Vec3> positions;
  std::vector<uint32_t> items;
  for (uint32_t f = 0; f < surfaces.faces.size(); ++f) {
    const SurfaceFace& face = surfaces.faces[f];
    const uint32_t item = itemOfFace(surfaces, f);
    if (item != f + 1) continue;
    const int corners = face.triangle ? 3 : 4;
    for (int t = 0; t + 2 < corners; ++t)
      for (int k : {0, t + 1, t + 2}) positions.push_back(face.corners[size_t(k)]), items.push_back(item);
  }
  m.vertexCount = GLsizei(positions.size());
  glCreateVertexArrays(1, &m.vao);
  glCreateBuffers(1, &m.positions);
  glCreateBuffers(1, &m.items);
  glNamedBufferStorage(m.positions, GLsizeiptr(std::max<size_t>(positions.size(), 1) * sizeof(Vec3)), positions.data(), 0);
  glNamedBufferStorage(m.items, GLsizeiptr(std::max<size_t>(items.size(), 1) * sizeof(uint32_t)), items.data(), 0);
  glVertexArrayVertexBuffer(m.vao, 0, m.positions, 0, sizeof(Vec3));
  glVertexArrayVertexBuffer(m.vao, 1, m.items, 0, sizeof(uint32_t));
  glEnableVertexArrayAttrib(m.vao, kPositionLocation);
  glEnableVertexArrayAttrib(m.vao, kItemLocation);
  glVertexArrayAttribFormat(m.vao, kPositionLocation, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribIFormat(m.vao, kItemLocation, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(m.vao, kPositionLocation, 0);
  glVertexArrayAttribBinding(m.vao, kItemLocation, 1);

  const GLsizei layers = 5 * hemicubes;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &m.itemLayers);
  glTextureStorage3D(m.itemLayers, 1, GL_R32UI, resolution, resolution, layers);
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &m.distanceLayers);
  glTextureStorage3D(m.distanceLayers, 1, GL_R32F, resolution, resolution, layers);
  for (GLuint t : {m.itemLayers, m.distanceLayers}) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // texelFetch only; integer textures need it
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glCreateRenderbuffers(1, &m.depth);
  glNamedRenderbufferStorage(m.depth, GL_DEPTH_COMPONENT32F, resolution, resolution);
  m.framebuffers.resize(size_t(layers));
  glCreateFramebuffers(layers, m.framebuffers.data());
  const GLenum drawBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  for (GLsizei l = 0; l < layers; ++l) {
    const GLuint fb = m.framebuffers[size_t(l)];
    glNamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT0, m.itemLayers, 0, l);
    glNamedFramebufferTextureLayer(fb, GL_COLOR_ATTACHMENT1, m.distanceLayers, 0, l);
    glNamedFramebufferRenderbuffer(fb, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m.depth);
    glNamedFramebufferDrawBuffers(fb, 2, drawBuffers);
    if (glCheckNamedFramebufferStatus(fb, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Error("OpenGL: the shooter hemicube framebuffer (R32UI + R32F + depth) is incomplete");
  }
  const std::string preamble = glslPreamble() + kHemicubeGlsl;
  m.program = std::make_unique<ShaderProgram>("shooter hemicube", preamble + kShooterVertex, preamble + kShooterFragment);
  m.layer = glGetUniformLocation(m.program->id(), "layer");
  m.program->use();
  glUniform1f(glGetUniformLocation(m.program->id(), "nearPlane"), near_);
  glUniform1f(glGetUniformLocation(m.program->id(), "farPlane"), far_);
  Context::check("creating the shooter hemicubes");
}

ShooterHemicubes::~ShooterHemicubes() = default;

void ShooterHemicubes::render(unsigned shooterBuffer, int count) {
  if (count < 0 || count > hemicubes_) throw Error(fmt::format("{} shooter hemicubes asked of {}", count, hemicubes_));
  Impl& m = *impl_;
  glViewport(0, 0, resolution_, resolution_);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // a surface blocks light from both sides
  m.program->use();
  glBindVertexArray(m.vao);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kShooterBinding, shooterBuffer);
  const GLuint noItem[4] = {0, 0, 0, 0};
  const GLfloat nothing[4] = {std::numeric_limits<float>::max(), 0, 0, 0};  // no surface: infinitely far
  for (int l = 0; l < 5 * count; ++l) {
    glBindFramebuffer(GL_FRAMEBUFFER, m.framebuffers[size_t(l)]);
    glUniform1i(m.layer, l);
    glClearBufferuiv(GL_COLOR, 0, noItem);
    glClearBufferfv(GL_COLOR, 1, nothing);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glDrawArrays(GL_TRIANGLES, 0, m.vertexCount);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ShooterHemicubes::bindTextures() const {
  glBindTextureUnit(kItemTextureUnit, impl_->itemLayers);
  glBindTextureUnit(kDistanceTextureUnit, impl_->distanceLayers);
}

}  // namespace luxel::gl
