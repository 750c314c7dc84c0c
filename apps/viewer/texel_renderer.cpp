#include "texel_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gl/gl_context.h"
#include "gl/shader_program.h"
#include "gl_mesh.h"
#include "hdr_target.h"
#include "view_shaders.h"

namespace luxel::viewer {
namespace {

struct Vertex {
  Vec3 position;
  Vec2 texel;  // texel units on its page
  float page;
  uint32_t element;  // an element of the face + 1 (0: none), so that a click picks what it shows
};

// A chart's hue: golden-ratio steps round the colour wheel, so neighbouring chart ids differ.
Rgb chartHue(uint32_t chart) {
  const float h = std::fmod(float(chart) * 0.6180339887f, 1.0f) * 6.0f;
  const float s = 0.45f, v = 0.85f;
  const float f = h - std::floor(h);
  const float p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  switch (int(h) % 6) {
    case 0: return {v, t, p};
    case 1: return {q, v, p};
    case 2: return {p, v, t};
    case 3: return {p, q, v};
    case 4: return {t, p, v};
    default: return {v, p, q};
  }
}

// What the view shows a texel as (linear RGB, shown as it is): its chart's hue or its fault's
// colour, darker on odd texels (the checker).
Rgb texelColour(const TexelDiagnostics& d, size_t page, int x, int y) {
  constexpr Rgb kInvalid{1.0f, 0.0f, 0.0f}, kOverlap{1.0f, 0.0f, 1.0f}, kBleed{1.0f, 0.85f, 0.0f};
  constexpr Rgb kUncovered{0.05f, 0.05f, 0.05f};
  const size_t i = size_t(y) * size_t(d.pageSize) + size_t(x);
  const uint8_t f = d.flags[page][i];
  const float checker = ((x + y) & 1) ? 0.7f : 1.0f;
  if (!(f & TexelDiagnostics::Covered)) return kUncovered;
  if (f & TexelDiagnostics::Overlap) return kOverlap * checker;
  if (f & TexelDiagnostics::Invalid) return kInvalid * checker;
  if (f & TexelDiagnostics::Bleed) return kBleed * checker;
  return chartHue(d.chart[page][i]) * checker;
}

}  // namespace

struct TexelRenderer::Gl {
  std::unique_ptr<gl::ShaderProgram> program;
  GLuint vao = 0, vbo = 0, ibo = 0, texels = 0;
  GLsizei indexCount = 0;
  ~Gl() {
    GLuint buffers[] = {vbo, ibo};
    glDeleteBuffers(2, buffers);
    glDeleteVertexArrays(1, &vao);
    glDeleteTextures(1, &texels);
  }
};

TexelRenderer::TexelRenderer(const Scene& scene, const SurfaceSet& surfaces, const LightmapAtlas& atlas,
                             const TexelDiagnostics& diagnostics, const std::filesystem::path& shaderDir)
    : gl_(std::make_unique<Gl>()) {
  Gl& g = *gl_;
  g.program = std::make_unique<gl::ShaderProgram>("viewer texels", shaderSource("texels.vert", shaderDir),
                                                  shaderSource("texels.frag", shaderDir));
  // Each scene face's first element in the solve's surfaces (+ 1): faces with no area have none.
  std::vector<std::vector<uint32_t>> elementOf(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) elementOf[m].assign(scene.meshes[m].faces.size(), 0);
  for (uint32_t e = uint32_t(surfaces.elements.size()); e-- > 0;) {
    const SurfaceFace& face = surfaces.faces[surfaces.elements[e].face];
    if (face.mesh < elementOf.size() && face.meshFace < elementOf[face.mesh].size()) elementOf[face.mesh][face.meshFace] = e + 1;
  }
  // Each face's own corners: a quad as the triangles 0-1-2 and 0-2-3, the atlas's (and the
  // bake's) split, so the texel mapping drawn is the one baked.
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      const Face& face = mesh.faces[f];
      const LightmapAtlas::FaceUv& uv = atlas.faces[m][f];
      const uint32_t base = uint32_t(vertices.size());
      for (int k = 0; k < face.vertexCount(); ++k)
        vertices.push_back({mesh.positions[face.v[size_t(k)]], uv.texel[size_t(k)], float(uv.page), elementOf[m][f]});
      indices.insert(indices.end(), {base, base + 1, base + 2});
      if (!face.isTriangle()) indices.insert(indices.end(), {base, base + 2, base + 3});
    }
  }
  g.indexCount = GLsizei(indices.size());
  const IndexedMesh mesh = makeIndexedMesh(
      vertices.data(), vertices.size(), sizeof(Vertex), indices,
      {{0, 3, offsetof(Vertex, position)},
       {1, 2, offsetof(Vertex, texel)},
       {2, 1, offsetof(Vertex, page)},
       {3, 1, offsetof(Vertex, element), true}});
  g.vao = mesh.vao, g.vbo = mesh.vbo, g.ibo = mesh.ibo;

  // One layer a page, a texel a texel: nearest, never filtered, so each texel shows whole.
  const int size = std::max(1, diagnostics.pageSize), pages = std::max<int>(1, int(diagnostics.flags.size()));
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &g.texels);
  glTextureStorage3D(g.texels, 1, GL_RGBA8, size, size, pages);
  glTextureParameteri(g.texels, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(g.texels, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(g.texels, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(g.texels, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  std::vector<uint8_t> rgba(size_t(size) * size_t(size) * 4);
  for (size_t p = 0; p < diagnostics.flags.size(); ++p) {
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const Rgb c = glm::clamp(texelColour(diagnostics, p, x, y), Rgb(0.0f), Rgb(1.0f));
        uint8_t* o = &rgba[(size_t(y) * size_t(size) + size_t(x)) * 4];
        o[0] = uint8_t(std::lround(c.r * 255.0f)), o[1] = uint8_t(std::lround(c.g * 255.0f));
        o[2] = uint8_t(std::lround(c.b * 255.0f)), o[3] = 255;
      }
    glTextureSubImage3D(g.texels, 0, 0, 0, GLint(p), size, size, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  }
  gl::Context::check("viewer: the texels view");
}

TexelRenderer::~TexelRenderer() = default;

void TexelRenderer::draw(const glm::mat4& viewProjection, float outputScale) {
  Gl& g = *gl_;
  beginOpaquePass();
  glDisable(GL_CULL_FACE);  // both sides: a face seen from behind still shows its texels
  g.program->use();
  const GLuint p = g.program->id();
  glUniformMatrix4fv(glGetUniformLocation(p, "uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
  glUniform1f(glGetUniformLocation(p, "uOutputScale"), outputScale);
  glBindTextureUnit(0, g.texels);
  glBindVertexArray(g.vao);
  glDrawElements(GL_TRIANGLES, g.indexCount, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);  // as found, for the GL solvers sharing the context
}

}  // namespace luxel::viewer
