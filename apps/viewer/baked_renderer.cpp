#include "baked_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

#include "gl/gl_context.h"
#include "gl/shader_program.h"
#include "gl_mesh.h"
#include "hdr_target.h"
#include "gl_texture.h"
#include "luxel/error.h"
#include "view_shaders.h"

namespace luxel::viewer {
namespace {

struct Vertex {
  Vec3 position;
  Vec2 uv0, uv1;
  Rgb color;
  Vec3 normal;
  glm::vec4 tangent;
  std::array<Vec3, 8> directions;  // LUXEL_vertex_directional's values, or zero
};

// baked.frag's uDirectional: the LUXEL_lightmap_directional modes.
int directionalCode(const std::string& mode) { return mode == "sh-l1" ? 1 : mode == "dominant" ? 2 : mode == "sh-l2" ? 3 : 0; }

// The baked view's "kinds" (baked.frag): what a primitive carries.
constexpr int kNothing = 0, kVertexRadiance = 1, kVertexIrradiance = 2, kLightmap = 3;

}  // namespace

struct BakedRenderer::Gl {
  std::unique_ptr<gl::ShaderProgram> program;
  GLuint vao = 0, vbo = 0, ibo = 0;
  struct Draw {
    GLsizei first = 0, count = 0;
    int material = -1;
    int kind = kNothing;
    bool directional = false;  // a directional lightmap under a normal map: read at the map's normal
    int vertexDirections = 0;  // directions per vertex under a normal map: the mode's code
    bool transfer = false;     // a transfer lightmap (LUXEL_lightmap_transfer) with all its pages
  };
  int transferBands = 0;
  std::vector<Rgb> transferLight;  // radiance SH, transferBands^2 coefficients
  std::vector<Draw> draws;
  std::vector<BakedGlb::Material> materials;
  std::vector<GLuint> srgb, linear;  // per image: as a base colour (sRGB) and as a lightmap (linear)
  std::vector<GLuint> normalMaps;    // per image: as a normal map (linear, repeated, mipmapped), or 0
  ~Gl() {
    GLuint buffers[] = {vbo, ibo};
    glDeleteBuffers(2, buffers);
    glDeleteVertexArrays(1, &vao);
    for (GLuint t : srgb) glDeleteTextures(1, &t);
    for (GLuint t : linear) glDeleteTextures(1, &t);
    for (GLuint t : normalMaps) glDeleteTextures(1, &t);
  }
};

BakedRenderer::BakedRenderer(const BakedGlb& glb, const std::filesystem::path& shaderDir) : gl_(std::make_unique<Gl>()) {
  Gl& g = *gl_;
  g.program = std::make_unique<gl::ShaderProgram>("viewer baked glb", shaderSource("baked.vert", shaderDir),
                                                  shaderSource("baked.frag", shaderDir));
  g.materials = glb.materials;
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  for (const BakedGlb::Primitive& p : glb.primitives) {
    Gl::Draw d;
    d.first = GLsizei(indices.size());
    d.material = p.material;
    const BakedGlb::Material* m = p.material >= 0 ? &glb.materials[size_t(p.material)] : nullptr;
    if (!p.colors.empty())
      d.kind = glb.vertexColors == "irradiance" ? kVertexIrradiance : kVertexRadiance;
    else if (m && (m->lightmap >= 0 || m->transferBands > 0) && !p.uv1.empty())
      d.kind = kLightmap;
    const uint32_t base = uint32_t(vertices.size());
    for (size_t i = 0; i < p.positions.size(); ++i)
      vertices.push_back({p.positions[i], p.uv0.empty() ? Vec2(0.0f) : p.uv0[i], p.uv1.empty() ? Vec2(0.0f) : p.uv1[i],
                          p.colors.empty() ? Rgb(0.0f) : p.colors[i], p.normals.empty() ? Vec3(0.0f) : p.normals[i],
                          p.tangents.empty() ? glm::vec4(0.0f) : p.tangents[i],
                          p.directions.empty() ? std::array<Vec3, 8>{} : p.directions[i]});
    d.directional = d.kind == kLightmap && m && !p.normals.empty() && !p.tangents.empty() && !p.uv0.empty() &&
                    m->normalTexture >= 0 && directionalCode(m->directionalMode) > 0;
    d.transfer = d.kind == kLightmap && m && m->transferBands > 0;
    if ((d.kind == kVertexRadiance || d.kind == kVertexIrradiance) && m && !p.directions.empty() && !p.normals.empty() && !p.tangents.empty() &&
        !p.uv0.empty() && m->normalTexture >= 0)
      d.vertexDirections = directionalCode(p.directionalMode);
    for (uint32_t i : p.indices) indices.push_back(base + i);
    d.count = GLsizei(indices.size()) - d.first;
    g.draws.push_back(d);
  }
  std::vector<VertexAttribute> attributes = {{0, 3, offsetof(Vertex, position)}, {1, 2, offsetof(Vertex, uv0)},
                                            {2, 2, offsetof(Vertex, uv1)},      {3, 3, offsetof(Vertex, color)},
                                            {4, 3, offsetof(Vertex, normal)},   {5, 4, offsetof(Vertex, tangent)}};
  for (unsigned k = 0; k < 8; ++k) attributes.push_back({6 + k, 3, offsetof(Vertex, directions) + k * sizeof(Vec3)});
  const IndexedMesh mesh = makeIndexedMesh(vertices.data(), vertices.size(), sizeof(Vertex), indices, attributes);
  g.vao = mesh.vao, g.vbo = mesh.vbo, g.ibo = mesh.ibo;
  // Base colour images are sRGB with mipmaps and repeat, lightmaps linear, clamped, unfiltered
  // across levels (docs/baking.md: sampled clamp-to-edge without mipmaps).
  for (const BakedGlb::Image& im : glb.images) {
    GLuint s = 0, l = 0;
    if (im.width > 0 && im.height > 0) {
      s = makeTexture({GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE, true, GL_REPEAT}, im.width, im.height, im.rgba.data());
      l = makeTexture({GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, false, GL_CLAMP_TO_EDGE}, im.width, im.height, im.rgba.data());
    }
    g.srgb.push_back(s);
    g.linear.push_back(l);
  }
  g.normalMaps.assign(glb.images.size(), 0);
  for (const BakedGlb::Material& m : glb.materials) {
    const int i = m.normalTexture;
    if (i < 0 || size_t(i) >= glb.images.size() || g.normalMaps[size_t(i)] || glb.images[size_t(i)].width <= 0) continue;
    const BakedGlb::Image& im = glb.images[size_t(i)];
    g.normalMaps[size_t(i)] = makeTexture({GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, true, GL_REPEAT}, im.width, im.height, im.rgba.data());
  }
  g.transferBands = glb.transfer.bands;
  gl::Context::check("viewer: the baked glb");
}

BakedRenderer::~BakedRenderer() = default;

void BakedRenderer::setTransferLight(const std::vector<Rgb>& sh) {
  if (sh.size() != size_t(gl_->transferBands * gl_->transferBands))
    throw Error(fmt::format("the transfer light has {} coefficients; the glb's {}-band transfer needs {}", sh.size(),
                            gl_->transferBands, gl_->transferBands * gl_->transferBands));
  gl_->transferLight = sh;
}

void BakedRenderer::draw(const glm::mat4& viewProjection, float outputScale) {
  Gl& g = *gl_;
  beginOpaquePass();
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  g.program->use();
  const GLuint p = g.program->id();
  auto loc = [&](const char* name) { return glGetUniformLocation(p, name); };
  glUniformMatrix4fv(loc("uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
  glUniform1f(loc("uOutputScale"), outputScale);
  glBindVertexArray(g.vao);
  for (const Gl::Draw& d : g.draws) {
    const BakedGlb::Material m = d.material >= 0 ? g.materials[size_t(d.material)] : BakedGlb::Material{};
    if (m.doubleSided) glDisable(GL_CULL_FACE);
    else glEnable(GL_CULL_FACE);
    glUniform1i(loc("uKind"), d.kind);
    glUniform4fv(loc("uBaseColor"), 1, glm::value_ptr(m.baseColor));
    glUniform3fv(loc("uEmission"), 1, glm::value_ptr(m.emission));
    glUniform1f(loc("uRgbmRange"), m.rgbmRange);
    const bool baseTexture = m.baseTexture >= 0 && size_t(m.baseTexture) < g.srgb.size() && g.srgb[size_t(m.baseTexture)];
    glUniform1i(loc("uBaseTexture"), baseTexture);
    if (baseTexture) glBindTextureUnit(0, g.srgb[size_t(m.baseTexture)]);
    if (d.kind == kLightmap && m.lightmap >= 0 && size_t(m.lightmap) < g.linear.size()) glBindTextureUnit(1, g.linear[size_t(m.lightmap)]);
    // Directional: the normal map (unit 2) and the direction textures (units 3..10), as data.
    auto linearImage = [&](int image) { return image >= 0 && size_t(image) < g.linear.size() ? g.linear[size_t(image)] : 0u; };
    // Transfer: band 0 in the lightmap's place (unit 1, RGBM), the ratio textures on units 3..14.
    const bool transfer = d.transfer && !g.transferLight.empty() && linearImage(m.transferBand0) != 0 &&
                          std::all_of(m.transferRatios.begin(), m.transferRatios.end(), [&](int i) { return linearImage(i) != 0; });
    glUniform1i(loc("uTransferBands"), transfer ? m.transferBands : 0);
    if (transfer) {
      glUniform1f(loc("uRgbmRange"), m.transferBand0Range);
      glBindTextureUnit(1, linearImage(m.transferBand0));
      for (size_t k = 0; k < m.transferRatios.size() && k < 12; ++k) glBindTextureUnit(GLuint(3 + k), linearImage(m.transferRatios[k]));
      glUniform1fv(loc("uRatioScale"), GLsizei(m.ratioScale.size()), m.ratioScale.data());
      glUniform3fv(loc("uLight"), GLsizei(g.transferLight.size()), glm::value_ptr(g.transferLight[0]));
    }
    const GLuint normalMap = m.normalTexture >= 0 && size_t(m.normalTexture) < g.normalMaps.size() ? g.normalMaps[size_t(m.normalTexture)] : 0u;
    const bool directional = d.directional && normalMap &&
                             std::all_of(m.directionImages.begin(), m.directionImages.end(), [&](int i) { return linearImage(i) != 0; });
    const bool vertexDirections = d.vertexDirections > 0 && normalMap;
    glUniform1i(loc("uDirectional"), directional ? directionalCode(m.directionalMode) : vertexDirections ? d.vertexDirections : 0);
    glUniform1i(loc("uVertexDirections"), vertexDirections);
    if (vertexDirections) {
      glUniform1f(loc("uNormalScale"), m.normalScale);
      glBindTextureUnit(2, normalMap);
    }
    if (directional) {
      glUniform1f(loc("uNormalScale"), m.normalScale);
      glBindTextureUnit(2, normalMap);
      for (size_t k = 0; k < m.directionImages.size() && k < 8; ++k) glBindTextureUnit(GLuint(3 + k), linearImage(m.directionImages[k]));
    }
    glDrawElements(GL_TRIANGLES, d.count, GL_UNSIGNED_INT, reinterpret_cast<const void*>(size_t(d.first) * sizeof(uint32_t)));
  }
  glDisable(GL_CULL_FACE);
  glBindVertexArray(0);
  glDepthFunc(GL_LESS);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
}

}  // namespace luxel::viewer
