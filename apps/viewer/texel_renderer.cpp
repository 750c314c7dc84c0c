#include "texel_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gl/gl_context.h"
#include "gl/shader_program.h"
#include "view_shaders.h"

namespace luxel::viewer {
namespace {

struct Vertex {
  Vec3 position;
  Vec2 texel;  // texel units on its page
  float page;
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

}  // namespace

Rgb texelColour(const TexelDiagnostics& d, size_t page, int x, int y) {
  const size_t i = size_t(y) * size_t(d.pageSize) + size_t(x);
  const uint8_t f = d.flags[page][i];
  const float checker = ((x + y) & 1) ? 0.7f : 1.0f;
  if (!(f & TexelDiagnostics::Covered)) return kUncoveredTexelColour;
  if (f & TexelDiagnostics::Overlap) return kOverlapTexelColour * checker;
  if (f & TexelDiagnostics::Invalid) return kInvalidTexelColour * checker;
  if (f & TexelDiagnostics::Bleed) return kBleedTexelColour * checker;
  return chartHue(d.chart[page][i]) * checker;
}

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

TexelRenderer::TexelRenderer(const Scene& scene, const LightmapAtlas& atlas, const TexelDiagnostics& diagnostics,
                             const std::filesystem::path& shaderDir)
    : gl_(std::make_unique<Gl>()) {
  Gl& g = *gl_;
  g.program = std::make_unique<gl::ShaderProgram>("viewer texels", shaderSource("texels.vert", shaderDir),
                                                  shaderSource("texels.frag", shaderDir));
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
        vertices.push_back({mesh.positions[face.v[size_t(k)]], uv.texel[size_t(k)], float(uv.page)});
      indices.insert(indices.end(), {base, base + 1, base + 2});
      if (!face.isTriangle()) indices.insert(indices.end(), {base, base + 2, base + 3});
    }
  }
  g.indexCount = GLsizei(indices.size());
  glCreateBuffers(1, &g.vbo);
  glNamedBufferStorage(g.vbo, GLsizeiptr(std::max<size_t>(16, vertices.size() * sizeof(Vertex))), vertices.empty() ? nullptr : vertices.data(), 0);
  glCreateBuffers(1, &g.ibo);
  glNamedBufferStorage(g.ibo, GLsizeiptr(std::max<size_t>(16, indices.size() * sizeof(uint32_t))), indices.empty() ? nullptr : indices.data(), 0);
  glCreateVertexArrays(1, &g.vao);
  glVertexArrayVertexBuffer(g.vao, 0, g.vbo, 0, sizeof(Vertex));
  glVertexArrayElementBuffer(g.vao, g.ibo);
  auto attribute = [&](GLuint index, GLint size, size_t offset) {
    glEnableVertexArrayAttrib(g.vao, index);
    glVertexArrayAttribFormat(g.vao, index, size, GL_FLOAT, GL_FALSE, GLuint(offset));
    glVertexArrayAttribBinding(g.vao, index, 0);
  };
  attribute(0, 3, offsetof(Vertex, position));
  attribute(1, 2, offsetof(Vertex, texel));
  attribute(2, 1, offsetof(Vertex, page));

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
  const float clearColour[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  const GLuint clearId[4] = {0, 0, 0, 0};
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);  // reversed depth, as SceneRenderer
  glClearBufferfv(GL_COLOR, 0, clearColour);
  glClearBufferuiv(GL_COLOR, 1, clearId);
  glClearBufferfi(GL_DEPTH_STENCIL, 0, 0.0f, 0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);  // both sides: a face seen from behind still shows its texels
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  g.program->use();
  const GLuint p = g.program->id();
  glUniformMatrix4fv(glGetUniformLocation(p, "uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
  glUniform1f(glGetUniformLocation(p, "uOutputScale"), outputScale);
  glBindTextureUnit(0, g.texels);
  glBindVertexArray(g.vao);
  glDrawElements(GL_TRIANGLES, g.indexCount, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

}  // namespace luxel::viewer
