#include "gl/layered_hemicubes.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <fmt/format.h>

#include "gl/gl_context.h"
#include "gl/hemicube_glsl.h"
#include "gl/item_mesh.h"
#include "gl/shader_program.h"
#include "gl/shared_layout.h"
#include "luxel/error.h"

namespace luxel::gl {
namespace {

// One instance per layer (hemicube x face): the vertex shader projects for the instance's face,
// and routes the triangle to that layer itself (VERTEX_LAYERS) or leaves that to the geometry
// shader, so that a whole pass is one draw into one layered framebuffer. (A framebuffer per
// layer, drawn one by one, measured 2.4x slower on llvmpipe once a few hundred had been used:
// every later pass paid for all of them.)
const char* kShooterVertex = R"(
layout(location = POSITION_LOCATION) in vec3 position;
layout(location = ITEM_LOCATION) in uint item;
layout(std430, binding = SHOOTER_BINDING) readonly buffer Shooters { GpuShooter shooters[]; };
uniform int first;
uniform float nearPlane, farPlane;
#ifdef VERTEX_LAYERS  // the layer set here (ARB_shader_viewport_layer_array): straight to the fragments
flat out uint vItem;
out vec3 vFromEye;
#define OUT_ITEM vItem
#define OUT_FROM_EYE vFromEye
#else
flat out uint gItem;
flat out int gLayer;
out vec3 gFromEye;
#define OUT_ITEM gItem
#define OUT_FROM_EYE gFromEye
#endif
void main() {
  const int layer = gl_InstanceID;
  GpuShooter s = shooters[first + layer / 5];
  OUT_ITEM = item;
#ifdef VERTEX_LAYERS
  gl_Layer = layer;
#else
  gLayer = layer;
#endif
  OUT_FROM_EYE = position - s.eye.xyz;
  gl_Position = s.ids.y == 0u ? vec4(2.0, 2.0, 2.0, 1.0)  // an empty slot: outside the clip volume
                              : hemicubeClip(position, s.eye.xyz, hemicubeFrame(s.normal.xyz, s.normal.w), layer % 5, nearPlane, farPlane);
}
)";

const char* kLayerGeometry = R"(
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
flat in uint gItem[];
flat in int gLayer[];
in vec3 gFromEye[];
flat out uint vItem;
out vec3 vFromEye;
void main() {
  // Wholly beyond one side of the clip volume: nothing to rasterise (most triangles of a scene,
  // for any one face of a hemicube).
  vec4 a = gl_in[0].gl_Position, b = gl_in[1].gl_Position, c = gl_in[2].gl_Position;
  if ((a.x > a.w && b.x > b.w && c.x > c.w) || (a.x < -a.w && b.x < -b.w && c.x < -c.w) ||
      (a.y > a.w && b.y > b.w && c.y > c.w) || (a.y < -a.w && b.y < -b.w && c.y < -c.w) ||
      (a.w <= 0.0 && b.w <= 0.0 && c.w <= 0.0))
    return;
  for (int i = 0; i < 3; ++i) {
    gl_Layer = gLayer[0];
    vItem = gItem[0];
    vFromEye = gFromEye[i];
    gl_Position = gl_in[i].gl_Position;
    EmitVertex();
  }
  EndPrimitive();
}
)";

const char* kItemDistanceFragment = R"(
flat in uint vItem;
in vec3 vFromEye;
layout(location = 0) out uint outItem;
layout(location = 1) out float outDistance;
void main() {
  outItem = vItem;
  outDistance = length(vFromEye);
}
)";

// The hemicube's projection keeps the winding, so a polygon counter-clockwise from its front
// is front facing here when seen from the side it radiates to.
const char* kRadiosityFragment = R"(
layout(std430, binding = PATCH_RADIOSITY_BINDING) readonly buffer Radiosity { vec4 radiosity[]; };
flat in uint vItem;
in vec3 vFromEye;
layout(location = 0) out uint outItem;
layout(location = 1) out vec4 outRadiosity;
void main() {
  outItem = vItem;
  outRadiosity = gl_FrontFacing ? radiosity[vItem - 1u] : vec4(0.0);
}
)";

}  // namespace

struct LayeredHemicubes::Impl {
  std::unique_ptr<ItemMesh> mesh;
  GLuint itemLayers = 0, distanceLayers = 0, depthLayers = 0;
  GLuint framebuffer = 0;  // all layers of the three, attached layered
  std::unique_ptr<ShaderProgram> program;
  GLint first = -1;

  ~Impl() {
    glDeleteFramebuffers(1, &framebuffer);
    const GLuint textures[3] = {itemLayers, distanceLayers, depthLayers};
    glDeleteTextures(3, textures);
  }
};

uint32_t LayeredHemicubes::itemOfFace(const SurfaceSet& surfaces, uint32_t face) {
  const int32_t twin = surfaces.faces[face].twin;
  return (twin >= 0 && uint32_t(twin) < face ? uint32_t(twin) : face) + 1;
}

void LayeredHemicubes::faceItems(const SurfaceSet& surfaces, std::vector<Polygon>& polygons,
                                 std::vector<uint32_t>& items) {
  for (uint32_t f = 0; f < surfaces.faces.size(); ++f) {
    const uint32_t item = itemOfFace(surfaces, f);
    if (item != f + 1) continue;  // its twin stands for both
    const SurfaceFace& face = surfaces.faces[f];
    Polygon p;
    p.count = face.triangle ? 3 : 4;
    for (int c = 0; c < p.count; ++c) p.v[size_t(c)] = face.corners[size_t(c)];
    polygons.push_back(p);
    items.push_back(item);
  }
}

void LayeredHemicubes::setPolygons(std::span<const Polygon> polygons, std::span<const uint32_t> items) {
  impl_->mesh = std::make_unique<ItemMesh>(polygons, items);
}

std::vector<uint32_t> LayeredHemicubes::neighbourItems(const SurfaceSet& surfaces) {
  // Corners meet where their positions agree to a millionth of the scene (a hash of the rounded
  // position); faces meeting at a corner are neighbours.
  const float cell = 1e-6f * std::max(surfaces.sceneExtent, 1e-6f);
  auto key = [cell](Vec3 p) {
    const auto q = [cell](float v) { return uint64_t(int64_t(std::llround(double(v) / double(cell)))); };
    return (q(p.x) * 0x9E3779B97F4A7C15ull) ^ (q(p.y) * 0xC2B2AE3D27D4EB4Full) ^ (q(p.z) * 0x165667B19E3779F9ull);
  };
  const size_t nf = surfaces.faces.size();
  std::unordered_map<uint64_t, std::vector<uint32_t>> facesAt;
  for (uint32_t f = 0; f < nf; ++f) {
    const SurfaceFace& face = surfaces.faces[f];
    for (int c = 0; c < (face.triangle ? 3 : 4); ++c) facesAt[key(face.corners[size_t(c)])].push_back(f);
  }
  std::vector<std::vector<uint32_t>> lists(nf);
  for (uint32_t f = 0; f < nf; ++f) {
    const SurfaceFace& face = surfaces.faces[f];
    std::vector<uint32_t>& list = lists[f];
    for (int c = 0; c < (face.triangle ? 3 : 4); ++c)
      for (uint32_t g : facesAt[key(face.corners[size_t(c)])]) {
        const uint32_t item = itemOfFace(surfaces, g);
        if (g != f && item != itemOfFace(surfaces, f) && list.size() < kMaxNeighbours &&
            std::find(list.begin(), list.end(), item) == list.end())
          list.push_back(item);
      }
  }
  std::vector<uint32_t> table(nf + 1);
  for (uint32_t f = 0; f < nf; ++f) table[f + 1] = table[f] + uint32_t(lists[f].size());
  for (uint32_t& t : table) t += uint32_t(nf + 1);
  for (const auto& list : lists) table.insert(table.end(), list.begin(), list.end());
  return table;
}

LayeredHemicubes::LayeredHemicubes(std::span<const Polygon> polygons, std::span<const uint32_t> polygonItems,
                                   Content content, int resolution, int capacity, float nearPlane, float farPlane,
                                   Layering layering)
    : impl_(std::make_unique<Impl>()), content_(content), resolution_(resolution), capacity_(capacity),
      near_(nearPlane), far_(farPlane) {
  GLint maxLayers = 0, vertexBlocks = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  glGetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &vertexBlocks);
  if (vertexBlocks < 1)
    throw Error("OpenGL: this driver has no shader storage in vertex shaders (GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS = 0), "
                "which GPU hemicubes need; use --backend cpu");
  if (resolution < 2 || resolution % 2 || resolution > 4096)
    throw Error(fmt::format("hemicube resolution {} must be even, from 2 to 4096", resolution));
  if (capacity < 1 || 5 * capacity > maxLayers)
    throw Error(fmt::format("{} hemicubes at once need {} texture layers; this OpenGL has {}", capacity,
                            5 * capacity, maxLayers));
  if (!(nearPlane > 0.0f && farPlane > nearPlane)) throw Error("hemicube near and far planes must be 0 < near < far");
  Impl& m = *impl_;

  m.mesh = std::make_unique<ItemMesh>(polygons, polygonItems);

  const GLsizei layers = 5 * capacity;
  const bool radiosity = content == Content::Radiosity;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &m.itemLayers);
  glTextureStorage3D(m.itemLayers, 1, GL_R32UI, resolution, resolution, layers);
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &m.distanceLayers);
  glTextureStorage3D(m.distanceLayers, 1, radiosity ? GL_RGBA32F : GL_R32F, resolution, resolution, layers);
  for (GLuint t : {m.itemLayers, m.distanceLayers}) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // texelFetch only; integer textures need it
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  }
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &m.depthLayers);
  glTextureStorage3D(m.depthLayers, 1, GL_DEPTH_COMPONENT32F, resolution, resolution, layers);
  glCreateFramebuffers(1, &m.framebuffer);
  glNamedFramebufferTexture(m.framebuffer, GL_COLOR_ATTACHMENT0, m.itemLayers, 0);
  glNamedFramebufferTexture(m.framebuffer, GL_COLOR_ATTACHMENT1, m.distanceLayers, 0);
  glNamedFramebufferTexture(m.framebuffer, GL_DEPTH_ATTACHMENT, m.depthLayers, 0);
  const GLenum drawBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(m.framebuffer, 2, drawBuffers);
  if (glCheckNamedFramebufferStatus(m.framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("OpenGL: the layered hemicube framebuffer (R32UI, R32F or RGBA32F, depth) is incomplete");
  const bool vertexLayers = epoxy_has_gl_extension("GL_ARB_shader_viewport_layer_array");
  if (layering == Layering::VertexShader && !vertexLayers)
    throw Error(fmt::format("OpenGL: hemicube layers from the vertex shader need GL_ARB_shader_viewport_layer_array, "
                            "which {} lacks; use the geometry shader's layering",
                            reinterpret_cast<const char*>(glGetString(GL_RENDERER))));
  layering_ = layering == Layering::GeometryShader || !vertexLayers ? Layering::GeometryShader : Layering::VertexShader;
  const std::string preamble = glslPreamble() + kHemicubeGlsl;
  const std::string fragment = preamble + (radiosity ? kRadiosityFragment : kItemDistanceFragment);
  const char* name = radiosity ? "radiosity hemicube" : "item and distance hemicube";
  if (layering_ == Layering::VertexShader) {
    // An #extension line must come before anything but other directives: right after #version.
    std::string vertex = preamble + kShooterVertex;
    vertex.insert(vertex.find('\n') + 1,
                  "#extension GL_ARB_shader_viewport_layer_array : require\n#define VERTEX_LAYERS\n");
    m.program = std::make_unique<ShaderProgram>(name, vertex, fragment);
  } else {
    m.program = std::make_unique<ShaderProgram>(name, preamble + kShooterVertex, preamble + kLayerGeometry, fragment);
  }
  m.first = glGetUniformLocation(m.program->id(), "first");
  m.program->use();
  glUniform1f(glGetUniformLocation(m.program->id(), "nearPlane"), near_);
  glUniform1f(glGetUniformLocation(m.program->id(), "farPlane"), far_);
  Context::check("creating layered hemicubes");
}

LayeredHemicubes::~LayeredHemicubes() = default;

void LayeredHemicubes::render(int first, int count) {
  if (first < 0 || count < 0 || count > capacity_)
    throw Error(fmt::format("{} hemicubes asked of {}", count, capacity_));
  Impl& m = *impl_;
  glViewport(0, 0, resolution_, resolution_);
  glEnable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // a surface blocks light from both sides
  m.program->use();
  glUniform1i(m.first, first);
  // No surface: id 0, infinitely far, and no light; only the layers drawn are cleared.
  const GLuint noItem = 0;
  const GLfloat far = std::numeric_limits<float>::max(), black[4] = {0.0f, 0.0f, 0.0f, 0.0f}, farDepth = 1.0f;
  const GLsizei layers = 5 * count;
  if (layers == 0) return;
  glClearTexSubImage(m.itemLayers, 0, 0, 0, 0, resolution_, resolution_, layers, GL_RED_INTEGER, GL_UNSIGNED_INT, &noItem);
  if (content_ == Content::Radiosity)
    glClearTexSubImage(m.distanceLayers, 0, 0, 0, 0, resolution_, resolution_, layers, GL_RGBA, GL_FLOAT, black);
  else
    glClearTexSubImage(m.distanceLayers, 0, 0, 0, 0, resolution_, resolution_, layers, GL_RED, GL_FLOAT, &far);
  glClearTexSubImage(m.depthLayers, 0, 0, 0, 0, resolution_, resolution_, layers, GL_DEPTH_COMPONENT, GL_FLOAT, &farDepth);
  glBindFramebuffer(GL_FRAMEBUFFER, m.framebuffer);
  m.mesh->drawInstanced(layers);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void LayeredHemicubes::bindTextures() const { bindTextures(kItemTextureUnit, kDistanceTextureUnit); }

void LayeredHemicubes::bindTextures(int itemUnit, int distanceUnit) const {
  glBindTextureUnit(GLuint(itemUnit), impl_->itemLayers);
  glBindTextureUnit(GLuint(distanceUnit), impl_->distanceLayers);
}

}  // namespace luxel::gl
