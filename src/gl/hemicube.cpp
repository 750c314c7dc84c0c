#include "gl/hemicube.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/gl_context.h"
#include "gl/item_mesh.h"
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

// One invocation per pixel row of the five faces (layer 0 the top, 1-4 the sides, whose lower
// half is below the receiver's plane and skipped). It walks the row and adds each run of one
// item's pixels with a single atomic: neighbouring pixels mostly show the same item, and atomics
// on one address serialise (one per pixel ran 2.8x slower than read-back on llvmpipe). The sums
// are integers, so the order of the additions cannot change them.
const char* kIntegrateCompute = R"(
layout(local_size_x = INTEGRATE_GROUP * INTEGRATE_GROUP, local_size_y = 1, local_size_z = 1) in;
layout(binding = ITEM_TEXTURE_UNIT) uniform usampler2DArray items;
layout(std430, binding = DELTA_BINDING) readonly buffer Deltas { uint deltas[]; };
layout(std430, binding = ITEM_SUM_BINDING) buffer ItemSums { uint itemSums[]; };
uniform int resolution;
void main() {
  const int row = int(gl_GlobalInvocationID.x), layer = int(gl_GlobalInvocationID.z);
  const int half_ = resolution / 2;
  if (row >= resolution || (layer > 0 && row < half_)) return;
  const int base = layer == 0 ? row * resolution : resolution * resolution + (row - half_) * resolution;
  uint current = 0u, sum = 0u;
  for (int x = 0; x < resolution; ++x) {
    const uint id = texelFetch(items, ivec3(x, row, layer), 0).r;
    if (id != current) {
      if (current != 0u) atomicAdd(itemSums[current - 1u], sum);
      current = id;
      sum = 0u;
    }
    sum += deltas[base + x];
  }
  if (current != 0u) atomicAdd(itemSums[current - 1u], sum);
}
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
  std::unique_ptr<ItemMesh> mesh;
  GLuint color = 0, depth = 0;
  GLuint framebuffers[5] = {};  // one per face, each on its layer of `color`
  GLuint deltaBuffer = 0, sumBuffer = 0;
  std::unique_ptr<ShaderProgram> program, integrate;
  GLint viewProjection = -1, integrateResolution = -1;
  float nearPlane = 0, farPlane = 0;
  std::vector<uint32_t> pixels;  // read-back faces, or the fixed-point sums

  ~Impl() {
    glDeleteFramebuffers(5, framebuffers);
    glDeleteBuffers(1, &deltaBuffer);
    glDeleteBuffers(1, &sumBuffer);
    glDeleteTextures(1, &color);
    glDeleteRenderbuffers(1, &depth);
  }
};

ItemHemicube::ItemHemicube(std::span<const Polygon> polygons, float sceneExtent, const HemicubeOptions& options)
    : impl_(std::make_unique<Impl>()), deltas_(options.resolution), polygonCount_(polygons.size()),
      integration_(options.integration) {
  if (!(options.nearPlane > 0.0f)) throw Error("hemicube near plane must be > 0");
  Impl& m = *impl_;
  const float extent = sceneExtent > 0.0f ? sceneExtent : 1.0f;
  m.nearPlane = options.nearPlane * extent;
  m.farPlane = 2.0f * extent;

  std::vector<uint32_t> ids(polygons.size());
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = uint32_t(i + 1);
  m.mesh = std::make_unique<ItemMesh>(polygons, ids);

  const int res = options.resolution;
  // The five faces are the layers of one R32UI array texture, so that one compute dispatch
  // integrates them all; they share one depth buffer, cleared per face.
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &m.color);
  glTextureStorage3D(m.color, 1, GL_R32UI, res, res, 5);
  // An integer texture with a linear filter is incomplete (texelFetch would read 0).
  glTextureParameteri(m.color, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(m.color, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glCreateRenderbuffers(1, &m.depth);
  glNamedRenderbufferStorage(m.depth, GL_DEPTH_COMPONENT32F, res, res);
  glCreateFramebuffers(5, m.framebuffers);
  for (int face = 0; face < 5; ++face) {
    glNamedFramebufferTextureLayer(m.framebuffers[face], GL_COLOR_ATTACHMENT0, m.color, 0, face);
    glNamedFramebufferRenderbuffer(m.framebuffers[face], GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m.depth);
    if (glCheckNamedFramebufferStatus(m.framebuffers[face], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Error("OpenGL: the hemicube framebuffer (R32UI + depth) is incomplete");
  }

  const std::string preamble = glslPreamble();
  m.program = std::make_unique<ShaderProgram>("item hemicube", preamble + kItemVertex, preamble + kItemFragment);
  m.viewProjection = glGetUniformLocation(m.program->id(), "viewProjection");
  if (integration_ == HemicubeIntegration::Compute) {
    m.integrate = std::make_unique<ShaderProgram>("hemicube integration", preamble + kIntegrateCompute);
    m.integrateResolution = glGetUniformLocation(m.integrate->id(), "resolution");
    // The delta tables in fixed point, uploaded once: top (res x res) then side (res x res/2).
    std::vector<uint32_t> fixed;
    fixed.reserve(deltas_.top.size() + deltas_.side.size());
    for (float f : deltas_.top) fixed.push_back(uint32_t(std::llround(double(f) * kFixedPointScale)));
    for (float f : deltas_.side) fixed.push_back(uint32_t(std::llround(double(f) * kFixedPointScale)));
    glCreateBuffers(1, &m.deltaBuffer);
    glNamedBufferStorage(m.deltaBuffer, GLsizeiptr(fixed.size() * sizeof(uint32_t)), fixed.data(), 0);
    glCreateBuffers(1, &m.sumBuffer);
    glNamedBufferStorage(m.sumBuffer, GLsizeiptr(std::max<size_t>(polygonCount_, 1) * sizeof(uint32_t)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    m.pixels.resize(std::max<size_t>(polygonCount_, 1));
  } else {
    m.pixels.resize(size_t(res) * res);
  }
  Context::check("creating the item hemicube");
}

ItemHemicube::~ItemHemicube() = default;

std::vector<float> ItemHemicube::formFactors(Vec3 p, Vec3 n) {
  std::vector<float> result(polygonCount_, 0.0f);
  render(p, n, result);
  return result;
}

void ItemHemicube::formFactors(Vec3 p, Vec3 n, std::span<float> out) {
  if (out.size() != polygonCount_)
    throw Error(fmt::format("hemicube: {} form factors asked for {} polygons", out.size(), polygonCount_));
  render(p, n, out);
}

void ItemHemicube::render(Vec3 p, Vec3 n, std::span<float> result) {
  Impl& m = *impl_;
  const int res = deltas_.resolution;
  const bool compute = integration_ == HemicubeIntegration::Compute;
  // An orthonormal frame round the normal.
  const Vec3 t = glm::normalize(std::abs(n.x) > 0.9f ? glm::cross(n, Vec3(0, 1, 0)) : glm::cross(n, Vec3(1, 0, 0)));
  const Vec3 b = glm::cross(n, t);
  const glm::mat4 projection = glm::perspective(0.5f * kPi, 1.0f, m.nearPlane, m.farPlane);

  std::fill(result.begin(), result.end(), 0.0f);
  glViewport(0, 0, res, res);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // a surface blocks light from both sides
  m.program->use();
  const GLuint clearItem[4] = {0, 0, 0, 0};
  const Vec3 directions[5] = {n, t, -t, b, -b};
  for (int face = 0; face < 5; ++face) {
    // Side faces look sideways with the normal up, so their upper half (rows res/2 and above)
    // is the part above the receiver's plane.
    const Vec3 up = face == 0 ? b : n;
    const glm::mat4 view = glm::lookAt(p, p + directions[face], up);
    const glm::mat4 viewProjection = projection * view;
    glBindFramebuffer(GL_FRAMEBUFFER, m.framebuffers[face]);
    glUniformMatrix4fv(m.viewProjection, 1, GL_FALSE, glm::value_ptr(viewProjection));
    glClearBufferuiv(GL_COLOR, 0, clearItem);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    m.mesh->draw();
    if (compute) continue;
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
  if (compute && polygonCount_ > 0) {
    // Rendering into the texture is ordered before the dispatch's texel fetches by GL itself;
    // the atomics into the sum buffer need a barrier before the read.
    const GLuint zero = 0;
    glClearNamedBufferData(m.sumBuffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    m.integrate->use();
    glUniform1i(m.integrateResolution, res);
    glBindTextureUnit(kItemTextureUnit, m.color);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kDeltaBinding, m.deltaBuffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kItemSumBinding, m.sumBuffer);
    const GLuint groupSize = GLuint(kIntegrateGroup * kIntegrateGroup);
    glDispatchCompute((GLuint(res) + groupSize - 1) / groupSize, 1, 5);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(m.sumBuffer, 0, GLsizeiptr(polygonCount_ * sizeof(uint32_t)), m.pixels.data());
    for (size_t i = 0; i < polygonCount_; ++i) result[i] = float(double(m.pixels[i]) / kFixedPointScale);
  }
  Context::check("rendering a hemicube");
}

}  // namespace luxel::gl
