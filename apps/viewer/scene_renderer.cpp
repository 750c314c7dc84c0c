#include "scene_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/gl_context.h"
#include "gl/shader_program.h"
#include "gl_texture.h"
#include "hdr_target.h"
#include "luxel/error.h"
#include "mesh/corner_groups.h"
#include "render/corner_values.h"
#include "scene/texture_decode.h"
#include "shadow_casters.h"
#include "view_shaders.h"

namespace luxel::viewer {
namespace {

constexpr const char* kModeNames[kViewModeCount] = {"final", "indirect", "direct", "radiosity", "patches", "elements", "density", "unshot", "baked", "texels"};
constexpr uint32_t kHasTwin = 1u, kTriangle = 2u;

struct Vertex {
  Vec3 position;
  Vec3 normal;        // the element's (flat): light arriving, as the solver and the ray caster see it
  Vec3 smoothNormal;  // averaged over the corner's smooth surface: the highlight's, on curved meshes
  Vec2 uv;
  Vec2 corner;
  uint32_t element;
  uint32_t flags;
};

struct CornerValues {
  glm::vec4 field, direct, perPixel;
};

// The four (u, v) corners of Embree's quad parameterisation, and the triangle's barycentrics.
constexpr Vec2 kQuadCorners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
constexpr Vec2 kTriangleCorners[4] = {{0, 0}, {1, 0}, {0, 1}, {0, 1}};

}  // namespace

ViewMode parseViewMode(const std::string& name) {
  for (int i = 0; i < kViewModeCount; ++i)
    if (name == kModeNames[i]) return ViewMode(i);
  throw Error(fmt::format("unknown view '{}' (expected final, indirect, direct, radiosity, patches, elements, density, unshot, baked or texels)", name));
}

const char* viewModeName(ViewMode mode) { return kModeNames[int(mode)]; }

bool drawnPerPixel(const Light& l) {
  return l.type == Light::Type::Point || l.type == Light::Type::Spot || l.type == Light::Type::Directional;
}

struct SceneRenderer::Gl {
  // One per view, count of per-pixel lights, per-vertex or per-pixel shading and pass, made when
  // first drawn, by their defines.
  std::map<std::string, std::unique_ptr<gl::ShaderProgram>> scenes;
  std::unique_ptr<gl::ShaderProgram> volume;
  GLuint casterVao = 0, casters = 0, casterIndices = 0;
  GLsizei casterIndexCount = 0;  // six a triangle (GL_TRIANGLES_ADJACENCY)
  std::unique_ptr<gl::ShaderProgram> cubeShadow, sunShadow, line, sky;
  GLuint skyVao = 0;
  Vec3 up{0.0f, 1.0f, 0.0f};
  Rgb uniformSky{0.0f}, overcastSky{0.0f};
  GLuint vao = 0, vbo = 0, ibo = 0, corners = 0, patchOf = 0, unshot = 0;
  GLuint lineVao = 0, elementEdges = 0, patchEdges = 0;
  GLsizei elementEdgeCount = 0, patchEdgeCount = 0, indexCount = 0;
  struct Batch {
    uint32_t material;
    GLsizei first, count;
  };
  std::vector<Batch> batches;
  std::vector<Material> materials;
  std::vector<GLuint> textures;  // per Scene::textures
  size_t elementCount = 0;
  Vec3 centre{0.0f};
  float radius = 1.0f;
  // Shadows and lights.
  GLuint cubeShadows = 0, sunShadows = 0, shadowFbo = 0;
  int cubeLayers = 0, sunLayers = 0;
  int lightCount = 0;
  glm::vec4 lightPosition[kMaxPerPixelLights]{}, lightPower[kMaxPerPixelLights]{}, lightSpot[kMaxPerPixelLights]{};
  float cosInner[kMaxPerPixelLights]{}, shadowFar[kMaxPerPixelLights]{}, shadowTexel[kMaxPerPixelLights]{};
  glm::mat4 sunMatrix[kMaxPerPixelLights]{};

  ~Gl() {
    GLuint buffers[] = {vbo, ibo, corners, patchOf, elementEdges, patchEdges, unshot};
    glDeleteBuffers(7, buffers);
    GLuint arrays[] = {vao, lineVao, skyVao, casterVao};
    glDeleteVertexArrays(4, arrays);
    glDeleteBuffers(1, &casters);
    glDeleteBuffers(1, &casterIndices);
    if (!textures.empty()) glDeleteTextures(GLsizei(textures.size()), textures.data());
    GLuint shadowTextures[] = {cubeShadows, sunShadows};
    glDeleteTextures(2, shadowTextures);
    glDeleteFramebuffers(1, &shadowFbo);
  }
};

SceneRenderer::SceneRenderer(const Scene& scene, const SurfaceSet& surfaces, std::filesystem::path shaderDir)
    : gl_(std::make_unique<Gl>()), shaderDir_(std::move(shaderDir)) {
  // Shadow maps are drawn again at every light edit: on llvmpipe a 1024^2 cube cost a lamp's move
  // 22 ms more than 512^2 (docs/performance.md, "The interactive viewer"); a GPU draws 2048^2 faces
  // in well under a millisecond.
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (renderer && !gl::isSoftwareRasteriser(renderer)) shadowSize_ = 2048, sunSize_ = 4096;
  buildPrograms();
  glCreateVertexArrays(1, &gl_->vao);
  glCreateVertexArrays(1, &gl_->lineVao);
  glCreateVertexArrays(1, &gl_->skyVao);
  glCreateVertexArrays(1, &gl_->casterVao);
  // Textures once: moves and new cuts keep the scene's images. Reflectance images (within [0, 1])
  // go to the GPU as 8-bit sRGB, decoded by the sampler: what the file held, at a quarter of float
  // RGB's bytes, which llvmpipe's trilinear filtering spends its time fetching (Sibenik's frame);
  // images with values above 1 (Radiance .hdr) as half floats.
  for (const Texture& t : scene.textures) {
    bool unit = true;
    for (const Rgb& c : t.texels) unit = unit && c.x <= 1.0f && c.y <= 1.0f && c.z <= 1.0f;
    if (unit) {
      std::vector<uint8_t> srgb(t.texels.size() * 4, 255);
      auto encode = [](float v) { return uint8_t(std::lround(linearToSrgb(v) * 255.0f)); };
      for (size_t i = 0; i < t.texels.size(); ++i)
        srgb[i * 4] = encode(t.texels[i].x), srgb[i * 4 + 1] = encode(t.texels[i].y), srgb[i * 4 + 2] = encode(t.texels[i].z);
      gl_->textures.push_back(makeTexture({GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE, true, GL_REPEAT}, t.width, t.height, srgb.data()));
    } else {
      gl_->textures.push_back(makeTexture({GL_RGB16F, GL_RGB, GL_FLOAT, true, GL_REPEAT}, t.width, t.height, t.texels.data()));
    }
  }
  glCreateFramebuffers(1, &gl_->shadowFbo);
  setGeometry(scene, surfaces);
  gl::Context::check("viewer: scene buffers");
}

SceneRenderer::~SceneRenderer() = default;

namespace {

std::string sceneDefines(ViewMode mode, int lights, bool lightOnly, bool perVertex, bool highlight) {
  return fmt::format("#define VIEW {}\n#define LIGHTS {}\n#define LIGHT_ONLY {}\n#define PER_VERTEX {}\n#define HIGHLIGHT {}\n",
                     int(mode), lights, lightOnly ? 1 : 0, perVertex ? 1 : 0, highlight ? 1 : 0);
}

}  // namespace

gl::ShaderProgram& SceneRenderer::sceneProgram(ViewMode mode, int lights, bool lightOnly, bool highlight) {
  const std::string defines = sceneDefines(mode, lights, lightOnly, perVertex_, highlight);
  std::unique_ptr<gl::ShaderProgram>& p = gl_->scenes[defines];
  if (!p)
    p = std::make_unique<gl::ShaderProgram>(
        fmt::format("viewer scene ({} view, {} lights{}{}{})", viewModeName(mode), lights, lightOnly ? ", one light's pass" : "",
                    perVertex_ ? ", per vertex" : "", highlight ? ", highlights" : ""),
        shaderSource("scene.vert", shaderDir_, defines), shaderSource("scene.frag", shaderDir_, defines));
  return *p;
}

void SceneRenderer::buildPrograms() {
  auto src = [&](const char* name) { return shaderSource(name, shaderDir_); };
  // The final view now, so that a shader that does not compile fails at once; the others when
  // first shown.
  const std::string finalDefines = sceneDefines(ViewMode::Final, 0, false, false, false);
  auto scene = std::make_unique<gl::ShaderProgram>("viewer scene (final view)", shaderSource("scene.vert", shaderDir_, finalDefines),
                                                   shaderSource("scene.frag", shaderDir_, finalDefines));
  auto cube = std::make_unique<gl::ShaderProgram>("viewer cube shadow", src("shadow.vert"), src("cube-shadow.frag"));
  auto sun = std::make_unique<gl::ShaderProgram>("viewer sun shadow", src("shadow.vert"), src("sun-shadow.frag"));
  auto line = std::make_unique<gl::ShaderProgram>("viewer edges", src("line.vert"), src("line.frag"));
  auto sky = std::make_unique<gl::ShaderProgram>("viewer sky", src("sky.vert"), src("sky.frag"));
  gl_->scenes.clear();
  gl_->volume = std::make_unique<gl::ShaderProgram>("viewer shadow volumes", src("volume.vert"), src("volume.geom"), src("volume.frag"));
  gl_->scenes[finalDefines] = std::move(scene);
  gl_->cubeShadow = std::move(cube);
  gl_->sunShadow = std::move(sun);
  gl_->line = std::move(line);
  gl_->sky = std::move(sky);
}

void SceneRenderer::reloadShaders() { buildPrograms(); }

void SceneRenderer::setGeometry(const Scene& scene, const SurfaceSet& surfaces) {
  Gl& g = *gl_;
  g.materials = scene.materials;
  g.elementCount = surfaces.elements.size();
  // Elements sorted by material, so that each material is one draw.
  std::vector<uint32_t> order(surfaces.elements.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return surfaces.elements[a].material < surfaces.elements[b].material;
  });
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices, patchOf(surfaces.elements.size());
  vertices.reserve(order.size() * 4);
  indices.reserve(order.size() * 6);
  g.batches.clear();
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  const CornerGroups groups(surfaces, kDefaultCreaseCosine);
  for (uint32_t e : order) {
    const Element& el = surfaces.elements[e];
    const SurfaceFace& face = surfaces.faces[el.face];
    patchOf[e] = el.patch;
    if (g.batches.empty() || g.batches.back().material != el.material)
      g.batches.push_back({el.material, GLsizei(indices.size()), 0});
    const bool triangle = el.polygon.count == 3;
    const uint32_t flags = (face.twin >= 0 ? kHasTwin : 0u) | (triangle ? kTriangle : 0u);
    const uint32_t base = uint32_t(vertices.size());
    for (int k = 0; k < 4; ++k) {
      const int c = std::min(k, el.polygon.count - 1);
      const Vec3 smooth = smoothCornerNormal(surfaces, groups, e, c);
      vertices.push_back({el.polygon.v[size_t(c)], el.normal, smooth, face.uv(el.param[size_t(c)]),
                          triangle ? kTriangleCorners[k] : kQuadCorners[k], e, flags});
      lo = glm::min(lo, el.polygon.v[size_t(c)]);
      hi = glm::max(hi, el.polygon.v[size_t(c)]);
    }
    if (triangle) {
      indices.insert(indices.end(), {base, base + 1, base + 2});
    } else {
      indices.insert(indices.end(), {base, base + 1, base + 3, base + 2, base + 3, base + 1});
    }
    g.batches.back().count = GLsizei(indices.size()) - g.batches.back().first;
  }
  g.centre = vertices.empty() ? Vec3(0.0f) : 0.5f * (lo + hi);
  g.radius = vertices.empty() ? 1.0f : std::max(0.5f * glm::length(hi - lo), 1e-6f);
  g.indexCount = GLsizei(indices.size());

  auto upload = [](GLuint& buffer, const void* data, size_t bytes) {
    glDeleteBuffers(1, &buffer);
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, GLsizeiptr(std::max<size_t>(bytes, 16)), bytes ? data : nullptr, GL_DYNAMIC_STORAGE_BIT);
  };
  upload(g.vbo, vertices.data(), vertices.size() * sizeof(Vertex));
  upload(g.ibo, indices.data(), indices.size() * sizeof(uint32_t));
  upload(g.patchOf, patchOf.data(), patchOf.size() * sizeof(uint32_t));
  std::vector<CornerValues> zero(surfaces.elements.size() * 4, CornerValues{});
  upload(g.corners, zero.data(), zero.size() * sizeof(CornerValues));
  const std::vector<float> noHeat(surfaces.elements.size(), 0.0f);
  upload(g.unshot, noHeat.data(), noHeat.size() * sizeof(float));

  GLuint vao = g.vao;
  glVertexArrayVertexBuffer(vao, 0, g.vbo, 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vao, g.ibo);
  auto attribute = [&](GLuint index, GLint size, GLenum type, size_t offset, bool integer) {
    glEnableVertexArrayAttrib(vao, index);
    if (integer)
      glVertexArrayAttribIFormat(vao, index, size, type, GLuint(offset));
    else
      glVertexArrayAttribFormat(vao, index, size, type, GL_FALSE, GLuint(offset));
    glVertexArrayAttribBinding(vao, index, 0);
  };
  attribute(0, 3, GL_FLOAT, offsetof(Vertex, position), false);
  attribute(1, 3, GL_FLOAT, offsetof(Vertex, normal), false);
  attribute(2, 2, GL_FLOAT, offsetof(Vertex, uv), false);
  attribute(3, 2, GL_FLOAT, offsetof(Vertex, corner), false);
  attribute(4, 1, GL_UNSIGNED_INT, offsetof(Vertex, element), true);
  attribute(5, 1, GL_UNSIGNED_INT, offsetof(Vertex, flags), true);
  attribute(6, 3, GL_FLOAT, offsetof(Vertex, smoothNormal), false);

  // Edges for the wireframe views: elements' and patches' outlines.
  std::vector<Vec3> lines;
  for (const Element& el : surfaces.elements)
    for (int k = 0; k < el.polygon.count; ++k) {
      lines.push_back(el.polygon.v[size_t(k)]);
      lines.push_back(el.polygon.v[size_t((k + 1) % el.polygon.count)]);
    }
  upload(g.elementEdges, lines.data(), lines.size() * sizeof(Vec3));
  g.elementEdgeCount = GLsizei(lines.size());
  lines.clear();
  for (const Patch& p : surfaces.patches)
    for (int k = 0; k < p.polygon.count; ++k) {
      lines.push_back(p.polygon.v[size_t(k)]);
      lines.push_back(p.polygon.v[size_t((k + 1) % p.polygon.count)]);
    }
  upload(g.patchEdges, lines.data(), lines.size() * sizeof(Vec3));
  g.patchEdgeCount = GLsizei(lines.size());
  // Shadow casters: the faces as triangles (coarser than the elements, the same surfaces), with
  // their neighbours, so that volumes get sides along silhouettes only (shadow_casters.h).
  const CasterMesh casters = casterMesh(surfaces);
  upload(g.casters, casters.vertices.data(), casters.vertices.size() * sizeof(Vec3));
  upload(g.casterIndices, casters.adjacency.data(), casters.adjacency.size() * sizeof(uint32_t));
  g.casterIndexCount = GLsizei(casters.adjacency.size());
  glVertexArrayElementBuffer(g.casterVao, g.casterIndices);
  glEnableVertexArrayAttrib(g.casterVao, 0);
  glVertexArrayAttribFormat(g.casterVao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(g.casterVao, 0, 0);
  glVertexArrayVertexBuffer(g.casterVao, 0, g.casters, 0, sizeof(Vec3));
  glEnableVertexArrayAttrib(g.lineVao, 0);
  glVertexArrayAttribFormat(g.lineVao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(g.lineVao, 0, 0);
  gl::Context::check("viewer: geometry");
}

void SceneRenderer::setFields(const std::vector<Rgb>& field, const std::vector<Rgb>& direct,
                              const std::vector<Rgb>& perPixel) {
  const size_t n = gl_->elementCount * 4;
  if (field.size() != n || direct.size() != n || perPixel.size() != n)
    throw Error(fmt::format("viewer: {} / {} / {} corner values for {} elements", field.size(), direct.size(),
                            perPixel.size(), gl_->elementCount));
  std::vector<CornerValues> corners(n);
  for (size_t i = 0; i < n; ++i)
    corners[i] = {glm::vec4(field[i], 0.0f), glm::vec4(direct[i], 0.0f), glm::vec4(perPixel[i], 0.0f)};
  glNamedBufferSubData(gl_->corners, 0, GLsizeiptr(n * sizeof(CornerValues)), corners.data());
}

void SceneRenderer::setUnshot(const std::vector<float>& heat) {
  std::vector<float> h = heat;
  h.resize(gl_->elementCount, 0.0f);
  glNamedBufferSubData(gl_->unshot, 0, GLsizeiptr(h.size() * sizeof(float)), h.data());
}

void SceneRenderer::setLights(const Scene& scene, const std::vector<uint32_t>& perPixel) {
  Gl& g = *gl_;
  if (perPixel.size() > size_t(kMaxPerPixelLights))
    throw Error(fmt::format("viewer: {} per-pixel lights, at most {}", perPixel.size(), kMaxPerPixelLights));
  g.lightCount = int(perPixel.size());
  g.up = glm::length(scene.up) > 0.0f ? glm::normalize(scene.up) : Vec3(0, 1, 0);
  g.uniformSky = g.overcastSky = Rgb(0.0f);
  for (const Light& l : scene.lights) {
    if (l.type == Light::Type::Sky) g.uniformSky += l.power();
    if (l.type == Light::Type::CieOvercastSky) g.overcastSky += l.power();
  }
  int cubes = 0, suns = 0;
  for (int i = 0; i < g.lightCount; ++i) {
    const Light& l = scene.lights.at(perPixel[size_t(i)]);
    const bool sun = l.type == Light::Type::Directional;
    const float type = sun ? 2.0f : l.type == Light::Type::Spot ? 1.0f : 0.0f;
    g.lightPosition[i] = glm::vec4(sun ? glm::normalize(l.direction) : l.position, type);
    g.lightPower[i] = glm::vec4(l.power(), float(sun ? suns++ : cubes++));
    g.lightSpot[i] = glm::vec4(glm::normalize(l.direction), std::cos(l.outerConeAngle));
    g.cosInner[i] = std::cos(l.innerConeAngle);
  }
  // Storage sized to the lights (a cube map array layer is a face; 6 per light).
  auto ensure = [&](GLuint& tex, GLenum target, int& layers, int want, int size, int depth) {
    if (want == 0 || layers == want) return;
    glDeleteTextures(1, &tex);
    glCreateTextures(target, 1, &tex);
    glTextureStorage3D(tex, 1, GL_DEPTH_COMPONENT32F, size, size, depth);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);  // 2x2 percentage-closer filtering
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(tex, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};  // beyond the sun's map: lit
    glTextureParameterfv(tex, GL_TEXTURE_BORDER_COLOR, white);
    layers = want;
  };
  ensure(g.cubeShadows, GL_TEXTURE_CUBE_MAP_ARRAY, g.cubeLayers, cubes, shadowSize_, 6 * cubes);
  ensure(g.sunShadows, GL_TEXTURE_2D_ARRAY, g.sunLayers, suns, sunSize_, suns);
  if (shadowMethod_ == ShadowMethod::Maps) drawShadows();
  gl::Context::check("viewer: shadow maps");
}

void SceneRenderer::drawShadows() {
  Gl& g = *gl_;
  glBindFramebuffer(GL_FRAMEBUFFER, g.shadowFbo);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);  // every face casts, whichever way it faces the light
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glBindVertexArray(g.vao);
  // The cube faces in OpenGL's order (+x, -x, +y, -y, +z, -z) with their conventional ups.
  const Vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const Vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  for (int i = 0; i < g.lightCount; ++i) {
    const int slot = int(g.lightPower[i].w);
    if (g.lightPosition[i].w == 2.0f) {
      // The sun: an orthographic map over the scene's bounding sphere.
      const Vec3 d = Vec3(g.lightPosition[i]);
      const Vec3 up = std::abs(d.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
      const glm::mat4 view = glm::lookAt(g.centre - d * (2.0f * g.radius), g.centre, up);
      const glm::mat4 proj = glm::ortho(-g.radius, g.radius, -g.radius, g.radius, g.radius * 0.5f, g.radius * 3.5f);
      const glm::mat4 vp = proj * view;
      // Clip space to [0,1]^3 for the lookup.
      const glm::mat4 bias = glm::translate(glm::mat4(1.0f), Vec3(0.5f)) * glm::scale(glm::mat4(1.0f), Vec3(0.5f));
      g.sunMatrix[i] = bias * vp;
      g.shadowTexel[i] = 2.0f * g.radius / float(sunSize_);
      glNamedFramebufferTextureLayer(g.shadowFbo, GL_DEPTH_ATTACHMENT, g.sunShadows, 0, slot);
      glViewport(0, 0, sunSize_, sunSize_);
      glClear(GL_DEPTH_BUFFER_BIT);
      g.sunShadow->use();
      glUniformMatrix4fv(glGetUniformLocation(g.sunShadow->id(), "uViewProjection"), 1, GL_FALSE, glm::value_ptr(vp));
      glDrawElements(GL_TRIANGLES, g.indexCount, GL_UNSIGNED_INT, nullptr);
      continue;
    }
    const Vec3 p = Vec3(g.lightPosition[i]);
    const float far = glm::length(p - g.centre) + g.radius;
    const float near = far * 1e-4f;
    g.shadowFar[i] = far;
    g.shadowTexel[i] = 1.0f / float(shadowSize_);  // tan of half a texel's angle, near the centre
    const glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, near, far);
    g.cubeShadow->use();
    glUniform3fv(glGetUniformLocation(g.cubeShadow->id(), "uLight"), 1, glm::value_ptr(p));
    glUniform1f(glGetUniformLocation(g.cubeShadow->id(), "uFar"), far);
    glViewport(0, 0, shadowSize_, shadowSize_);
    for (int f = 0; f < 6; ++f) {
      glNamedFramebufferTextureLayer(g.shadowFbo, GL_DEPTH_ATTACHMENT, g.cubeShadows, 0, slot * 6 + f);
      glClear(GL_DEPTH_BUFFER_BIT);
      const glm::mat4 vp = proj * glm::lookAt(p, p + dirs[f], ups[f]);
      glUniformMatrix4fv(glGetUniformLocation(g.cubeShadow->id(), "uViewProjection"), 1, GL_FALSE, glm::value_ptr(vp));
      glDrawElements(GL_TRIANGLES, g.indexCount, GL_UNSIGNED_INT, nullptr);
    }
  }
}

void SceneRenderer::drawSky(const Frame& f) {
  Gl& g = *gl_;
  if (g.uniformSky == Rgb(0.0f) && g.overcastSky == Rgb(0.0f)) return;
  // After the surfaces, at infinity (depth 0, what the depth buffer was cleared to): only the
  // pixels no surface covers pass, so the sky costs what is seen of it.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GEQUAL);
  glDepthMask(GL_FALSE);
  g.sky->use();
  const GLuint sp = g.sky->id();
  const glm::mat4 inverse = glm::inverse(f.viewProjection);
  glUniformMatrix4fv(glGetUniformLocation(sp, "uInverseViewProjection"), 1, GL_FALSE, glm::value_ptr(inverse));
  glUniform3fv(glGetUniformLocation(sp, "uUp"), 1, glm::value_ptr(g.up));
  glUniform3fv(glGetUniformLocation(sp, "uUniform"), 1, glm::value_ptr(g.uniformSky));
  glUniform3fv(glGetUniformLocation(sp, "uOvercast"), 1, glm::value_ptr(g.overcastSky));
  glUniform1f(glGetUniformLocation(sp, "uOutputScale"), f.outputScale);
  glBindVertexArray(g.skyVao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void SceneRenderer::drawSurfaces(const Frame& f, int lights, bool lightOnly, int first, bool withShadowMaps) {
  Gl& g = *gl_;
  const int count = lights;
  // Two programs: with the highlight (materials that have one) and without, which llvmpipe would
  // otherwise pay for on every surface (a branch on a uniform runs under a mask).
  gl::ShaderProgram* programs[2] = {&sceneProgram(f.mode, lights, lightOnly, false),
                                    count > 0 ? &sceneProgram(f.mode, lights, lightOnly, true) : nullptr};
  glm::vec4 power[kMaxPerPixelLights];
  for (int i = 0; i < count; ++i) {
    power[i] = g.lightPower[first + i];
    if (!withShadowMaps) power[i].w = -1.0f;  // no map: the stencil decides
  }
  for (gl::ShaderProgram* program : programs) {
    if (!program) continue;
    program->use();
    const GLuint prog = program->id();
    auto loc = [&](const char* name) { return glGetUniformLocation(prog, name); };
    glUniformMatrix4fv(loc("uViewProjection"), 1, GL_FALSE, glm::value_ptr(f.viewProjection));
    glUniform3fv(loc("uEye"), 1, glm::value_ptr(f.eye));
    glUniform1f(loc("uOutputScale"), f.outputScale);
    glUniform1f(loc("uTexelSize"), f.texelSize);
    if (count > 0) {
      glUniform4fv(loc("uLightPosition"), count, glm::value_ptr(g.lightPosition[first]));
      glUniform4fv(loc("uLightPower"), count, glm::value_ptr(power[0]));
      glUniform4fv(loc("uLightSpot"), count, glm::value_ptr(g.lightSpot[first]));
      glUniform1fv(loc("uLightCosInner"), count, g.cosInner + first);
      glUniform1fv(loc("uShadowFar"), count, g.shadowFar + first);
      glUniform1fv(loc("uShadowTexel"), count, g.shadowTexel + first);
      glUniformMatrix4fv(loc("uSunMatrix"), count, GL_FALSE, glm::value_ptr(g.sunMatrix[first]));
    }
  }
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, g.corners);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, g.patchOf);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, g.unshot);
  if (g.cubeShadows) glBindTextureUnit(2, g.cubeShadows);
  if (g.sunShadows) glBindTextureUnit(3, g.sunShadows);
  glBindVertexArray(g.vao);
  gl::ShaderProgram* bound = nullptr;
  for (const Gl::Batch& b : g.batches) {
    const Material& m = g.materials[b.material];
    gl::ShaderProgram* program = m.hasSpecular() && programs[1] ? programs[1] : programs[0];
    if (program != bound) program->use(), bound = program;
    const GLuint prog = program->id();
    auto loc = [&](const char* name) { return glGetUniformLocation(prog, name); };
    glUniform3fv(loc("uReflectance"), 1, glm::value_ptr(m.reflectance));
    glUniform3fv(loc("uEmission"), 1, glm::value_ptr(m.emission));
    glUniform3fv(loc("uSpecular"), 1, glm::value_ptr(m.specular));
    glUniform1f(loc("uShininess"), m.shininess);
    const bool rt = m.reflectanceTexture >= 0 && size_t(m.reflectanceTexture) < g.textures.size();
    const bool et = m.isEmissive() && m.emissionTexture >= 0 && size_t(m.emissionTexture) < g.textures.size();
    glUniform1i(loc("uReflectanceTexture"), rt);
    glUniform1i(loc("uEmissionTexture"), et);
    if (rt) glBindTextureUnit(0, g.textures[size_t(m.reflectanceTexture)]);
    if (et) glBindTextureUnit(1, g.textures[size_t(m.emissionTexture)]);
    glDrawElements(GL_TRIANGLES, b.count, GL_UNSIGNED_INT, reinterpret_cast<const void*>(size_t(b.first) * sizeof(uint32_t)));
  }
}

void SceneRenderer::drawVolumes(const Frame& f, int light) {
  Gl& g = *gl_;
  const bool sun = g.lightPosition[light].w == 2.0f;
  const glm::vec4 l = sun ? glm::vec4(Vec3(g.lightPosition[light]), 0.0f) : glm::vec4(Vec3(g.lightPosition[light]), 1.0f);
  g.volume->use();
  glUniformMatrix4fv(glGetUniformLocation(g.volume->id(), "uViewProjection"), 1, GL_FALSE, glm::value_ptr(f.viewProjection));
  glUniform4fv(glGetUniformLocation(g.volume->id(), "uLight"), 1, glm::value_ptr(l));
  glBindVertexArray(g.casterVao);
  glDrawElements(GL_TRIANGLES_ADJACENCY, g.casterIndexCount, GL_UNSIGNED_INT, nullptr);
}

void SceneRenderer::drawEdges(const Frame& f) {
  Gl& g = *gl_;
  if (!f.elementEdges && !f.patchEdges) return;
  g.line->use();
  const GLuint lp = g.line->id();
  glUniformMatrix4fv(glGetUniformLocation(lp, "uViewProjection"), 1, GL_FALSE, glm::value_ptr(f.viewProjection));
  glDepthFunc(GL_GEQUAL);
  glBindVertexArray(g.lineVao);
  glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);  // edges are not pickable
  auto edges = [&](GLuint buffer, GLsizei count, glm::vec4 colour) {
    glVertexArrayVertexBuffer(g.lineVao, 0, buffer, 0, sizeof(Vec3));
    glUniform4fv(glGetUniformLocation(lp, "uColour"), 1, glm::value_ptr(colour));
    glDrawArrays(GL_LINES, 0, count);
  };
  // Element edges black; patch edges yellow and far brighter than any radiance shown (1e4 times the
  // exposure's middle grey), so the tone curve draws them at full yellow.
  if (f.elementEdges) edges(g.elementEdges, g.elementEdgeCount, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  if (f.patchEdges) edges(g.patchEdges, g.patchEdgeCount, glm::vec4(1e4f, 1e4f, 0.0f, 1.0f));
  glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void SceneRenderer::draw(const Frame& f) {
  Gl& g = *gl_;
  // Reversed depth (ViewCamera::projection): put back as found at the end, for the GL solvers
  // that share the context.
  beginOpaquePass();
  glDisable(GL_CULL_FACE);  // backs are drawn black or left to their twins (scene.frag)
  const bool perPixelView = f.mode == ViewMode::Final || f.mode == ViewMode::Direct;
  const bool volumes = shadowMethod_ == ShadowMethod::Volumes && perPixelView && g.lightCount > 0;
  if (!volumes) {
    drawSurfaces(f, perPixelView ? g.lightCount : 0, false, 0, true);
  } else {
    // 004's path: the light that needs no shadows first (the field and emission), then for each
    // light its shadow volumes into the stencil (z-fail: counted where they lie behind what is
    // seen) and its light added where the count is zero.
    drawSurfaces(f, 0, false, 0, false);
    glDepthMask(GL_FALSE);
    glEnable(GL_STENCIL_TEST);
    for (int i = 0; i < g.lightCount; ++i) {
      glClear(GL_STENCIL_BUFFER_BIT);
      glColorMaski(0, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      glDepthFunc(GL_GREATER);
      glStencilFunc(GL_ALWAYS, 0, 0xFF);
      glStencilOpSeparate(GL_BACK, GL_KEEP, GL_INCR_WRAP, GL_KEEP);
      glStencilOpSeparate(GL_FRONT, GL_KEEP, GL_DECR_WRAP, GL_KEEP);
      drawVolumes(f, i);
      glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      glStencilFunc(GL_EQUAL, 0, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
      glDepthFunc(GL_GEQUAL);  // the surfaces seen, drawn again (invariant positions)
      glEnablei(GL_BLEND, 0);
      glBlendFunci(0, GL_ONE, GL_ONE);
      drawSurfaces(f, 1, true, i, false);
      glDisablei(GL_BLEND, 0);
    }
    glDisable(GL_STENCIL_TEST);
    glDepthMask(GL_TRUE);
  }
  drawSky(f);
  drawEdges(f);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
}

ShadowMethod parseShadowMethod(const std::string& name) {
  if (name == "maps") return ShadowMethod::Maps;
  if (name == "volumes") return ShadowMethod::Volumes;
  throw Error(fmt::format("unknown shadow method '{}' (expected maps or volumes)", name));
}

const char* shadowMethodName(ShadowMethod m) { return m == ShadowMethod::Maps ? "maps" : "volumes"; }

void SceneRenderer::setPerVertex(bool perVertex) { perVertex_ = perVertex; }

void SceneRenderer::setShadowMethod(ShadowMethod method) {
  if (method == shadowMethod_) return;
  shadowMethod_ = method;
  if (method == ShadowMethod::Maps) drawShadows();
}

}  // namespace luxel::viewer
