#include "gl/hemicube.h"

#include <epoxy/gl.h>

#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/gl_context.h"
#include "gl/shader_program.h"
#include "gl/shared_layout.h"
#include "luxel/error.h"

namespace luxel::gl {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

const char* kItemVertex = R"(
layout(location = POSITION_LOCATION) in vec3 position;
layout(location = ITEM_LOCATION) in uint item;
uniform mat4 viewProjection;
flat out uint vItem;
void main() {
  vItem = item;
  gl_Position = viewProjection * vec4(position, 1.0);
}
)";

const char* kItemFragment = R"(
flat in uint vItem;
layout(location = 0) out uint outItem;
void main() { outItem = vItem; }
)";

}  // namespace

DeltaFormFactors::DeltaFormFactors(int res) : resolution(res) {
  if (res < 2 || res % 2 != 0 || res > 4096)
    throw Error(fmt::format("hemicube resolution {} must be even, from 2 to 4096", res));
  const double dA = (2.0 / res) * (2.0 / res);
  top.resize(size_t(res) * res);
  side.resize(size_t(res) * (res / 2));
  double sum = 0.0;
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i) {
      const double x = 2.0 * (i + 0.5) / res - 1.0, y = 2.0 * (j + 0.5) / res - 1.0;
      const double d = x * x + y * y + 1.0;
      const double f = dA / (std::numbers::pi * d * d);
      top[size_t(j) * res + i] = float(f);
      sum += f;
    }
  for (int j = 0; j < res / 2; ++j)
    for (int i = 0; i < res; ++i) {
      const double x = 2.0 * (i + 0.5) / res - 1.0, z = 2.0 * (j + 0.5) / res;
      const double d = x * x + z * z + 1.0;
      const double f = z * dA / (std::numbers::pi * d * d);
      side[size_t(j) * res + i] = float(f);
      sum += 4.0 * f;
    }
  rawSum = sum;
  for (float& f : top) f = float(f / sum);
  for (float& f : side) f = float(f / sum);
}

struct ItemHemicube::Impl {
  GLuint vao = 0, positions = 0, items = 0, framebuffer = 0, color = 0, depth = 0;
  GLsizei vertexCount = 0;
  std::unique_ptr<ShaderProgram> program;
  GLint viewProjection = -1;
  float nearPlane = 0, farPlane = 0;
  std::vector<uint32_t> pixels;

  ~Impl() {
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(1, &color);
    glDeleteRenderbuffers(1, &depth);
    glDeleteBuffers(1, &positions);
    glDeleteBuffers(1, &items);
    glDeleteVertexArrays(1, &vao);
  }
};

ItemHemicube::ItemHemicube(std::span<const Polygon> polygons, float sceneExtent, const HemicubeOptions& options)
    : impl_(std::make_unique<Impl>()), deltas_(options.resolution), polygonCount_(polygons.size()) {
  if (!(options.nearPlane > 0.0f)) throw Error("hemicube near plane must be > 0");
  Impl& m = *impl_;
  const float extent = sceneExtent > 0.0f ? sceneExtent : 1.0f;
  m.nearPlane = options.nearPlane * extent;
  m.farPlane = 2.0f * extent;

  // Triangles with a flat item id per vertex (quads split along 0-2, as the ray tracer's quads).
  std::vector<Vec3> positions;
  std::vector<uint32_t> items;
  for (size_t i = 0; i < polygons.size(); ++i) {
    const Polygon& p = polygons[i];
    const uint32_t id = uint32_t(i + 1);
    for (int t = 0; t + 2 < p.count; ++t) {
      for (int k : {0, t + 1, t + 2}) positions.push_back(p.v[size_t(k)]), items.push_back(id);
    }
  }
  m.vertexCount = GLsizei(positions.size());
  glCreateVertexArrays(1, &m.vao);
  glCreateBuffers(1, &m.positions);
  glCreateBuffers(1, &m.items);
  glNamedBufferStorage(m.positions, GLsizeiptr(positions.size() * sizeof(Vec3)), positions.data(), 0);
  glNamedBufferStorage(m.items, GLsizeiptr(items.size() * sizeof(uint32_t)), items.data(), 0);
  glVertexArrayVertexBuffer(m.vao, 0, m.positions, 0, sizeof(Vec3));
  glVertexArrayVertexBuffer(m.vao, 1, m.items, 0, sizeof(uint32_t));
  glEnableVertexArrayAttrib(m.vao, kPositionLocation);
  glEnableVertexArrayAttrib(m.vao, kItemLocation);
  glVertexArrayAttribFormat(m.vao, kPositionLocation, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribIFormat(m.vao, kItemLocation, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(m.vao, kPositionLocation, 0);
  glVertexArrayAttribBinding(m.vao, kItemLocation, 1);

  const int res = options.resolution;
  glCreateTextures(GL_TEXTURE_2D, 1, &m.color);
  glTextureStorage2D(m.color, 1, GL_R32UI, res, res);
  glCreateRenderbuffers(1, &m.depth);
  glNamedRenderbufferStorage(m.depth, GL_DEPTH_COMPONENT32F, res, res);
  glCreateFramebuffers(1, &m.framebuffer);
  glNamedFramebufferTexture(m.framebuffer, GL_COLOR_ATTACHMENT0, m.color, 0);
  glNamedFramebufferRenderbuffer(m.framebuffer, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m.depth);
  if (glCheckNamedFramebufferStatus(m.framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("OpenGL: the hemicube framebuffer (R32UI + depth) is incomplete");

  const std::string preamble = glslPreamble();
  m.program = std::make_unique<ShaderProgram>("item hemicube", preamble + kItemVertex, preamble + kItemFragment);
  m.viewProjection = glGetUniformLocation(m.program->id(), "viewProjection");
  m.pixels.resize(size_t(res) * res);
  Context::check("creating the item hemicube");
}

ItemHemicube::~ItemHemicube() = default;

std::vector<float> ItemHemicube::formFactors(Vec3 p, Vec3 n) {
  Impl& m = *impl_;
  const int res = deltas_.resolution;
  // An orthonormal frame round the normal.
  const Vec3 t = glm::normalize(std::abs(n.x) > 0.9f ? glm::cross(n, Vec3(0, 1, 0)) : glm::cross(n, Vec3(1, 0, 0)));
  const Vec3 b = glm::cross(n, t);
  const glm::mat4 projection = glm::perspective(0.5f * kPi, 1.0f, m.nearPlane, m.farPlane);

  std::vector<float> result(polygonCount_, 0.0f);
  glBindFramebuffer(GL_FRAMEBUFFER, m.framebuffer);
  glViewport(0, 0, res, res);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // a surface blocks light from both sides
  m.program->use();
  glBindVertexArray(m.vao);
  const GLuint clearItem[4] = {0, 0, 0, 0};
  const Vec3 directions[5] = {n, t, -t, b, -b};
  for (int face = 0; face < 5; ++face) {
    // Side faces look sideways with the normal up, so their upper half (rows res/2 and above)
    // is the part above the receiver's plane.
    const Vec3 up = face == 0 ? b : n;
    const glm::mat4 view = glm::lookAt(p, p + directions[face], up);
    const glm::mat4 viewProjection = projection * view;
    glUniformMatrix4fv(m.viewProjection, 1, GL_FALSE, glm::value_ptr(viewProjection));
    glClearBufferuiv(GL_COLOR, 0, clearItem);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glDrawArrays(GL_TRIANGLES, 0, m.vertexCount);
    glReadPixels(0, 0, res, res, GL_RED_INTEGER, GL_UNSIGNED_INT, m.pixels.data());
    if (face == 0) {
      for (size_t i = 0; i < m.pixels.size(); ++i)
        if (m.pixels[i]) result[m.pixels[i] - 1] += deltas_.top[i];
    } else {
      for (int j = res / 2; j < res; ++j)
        for (int i = 0; i < res; ++i)
          if (uint32_t id = m.pixels[size_t(j) * res + i]) result[id - 1] += deltas_.side[size_t(j - res / 2) * res + i];
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  Context::check("rendering a hemicube");
  return result;
}

}  // namespace luxel::gl
