// glTF 2.0 binary output through tinygltf (Debian's libtinygltf-dev, its implementation in the
// shared library: no TINYGLTF_IMPLEMENTATION here). Everything goes into the glb's one binary
// chunk: one buffer view per accessor, images as PNG buffer views.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <sstream>
#include <limits>
#include <map>
#include <unordered_map>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>
#include <stb_image_write.h>
#include <tiny_gltf.h>

#include "io/atomic_file.h"
#include "luxel/bake.h"
#include "luxel/error.h"
#include "render/normal_map.h"
#include "scene/texture_decode.h"

namespace luxel {
namespace {

constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

// Appends `bytes` to the model's one buffer as a new buffer view (4-byte aligned); returns its index.
int addBufferView(tinygltf::Model& model, const void* bytes, size_t size, int target) {
  std::vector<unsigned char>& data = model.buffers[0].data;
  while (data.size() % 4 != 0) data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  const auto* p = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), p, p + size);
  model.bufferViews.push_back(view);
  return int(model.bufferViews.size()) - 1;
}

template <int N>
int addFloatAccessor(tinygltf::Model& model, const std::vector<std::array<float, N>>& values, int type,
                     bool withBounds) {
  tinygltf::Accessor a;
  a.bufferView = addBufferView(model, values.data(), values.size() * sizeof(values[0]), kArrayBuffer);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.count = values.size();
  a.type = type;
  if (withBounds) {  // POSITION must carry min and max
    a.minValues.assign(N, std::numeric_limits<double>::max());
    a.maxValues.assign(N, -std::numeric_limits<double>::max());
    for (const auto& v : values)
      for (int i = 0; i < N; ++i) {
        a.minValues[size_t(i)] = std::min(a.minValues[size_t(i)], double(v[size_t(i)]));
        a.maxValues[size_t(i)] = std::max(a.maxValues[size_t(i)], double(v[size_t(i)]));
      }
  }
  model.accessors.push_back(a);
  return int(model.accessors.size()) - 1;
}

int addIndexAccessor(tinygltf::Model& model, const std::vector<uint32_t>& indices, size_t vertexCount) {
  tinygltf::Accessor a;
  if (vertexCount <= 65535) {
    std::vector<uint16_t> small(indices.begin(), indices.end());
    a.bufferView = addBufferView(model, small.data(), small.size() * 2, kElementArrayBuffer);
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  } else {
    a.bufferView = addBufferView(model, indices.data(), indices.size() * 4, kElementArrayBuffer);
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  }
  a.count = indices.size();
  a.type = TINYGLTF_TYPE_SCALAR;
  model.accessors.push_back(a);
  return int(model.accessors.size()) - 1;
}

void appendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<uint8_t>*>(context);
  const auto* p = static_cast<const uint8_t*>(data);
  out->insert(out->end(), p, p + size);
}

// A linear texture as an 8-bit sRGB PNG, top row first (glTF's v = 0 is the image's top); `data`
// (a normal map): the values as they are, no transfer curve.
std::vector<uint8_t> encodeTexture(const Texture& tex, bool data = false) {
  std::vector<uint8_t> rgb(size_t(tex.width) * size_t(tex.height) * 3);
  for (int y = 0; y < tex.height; ++y)
    for (int x = 0; x < tex.width; ++x) {
      const Rgb& c = tex.texels[size_t(tex.height - 1 - y) * size_t(tex.width) + size_t(x)];
      for (int k = 0; k < 3; ++k)
        rgb[(size_t(y) * size_t(tex.width) + size_t(x)) * 3 + size_t(k)] =
            uint8_t(std::lround(255.0f * std::clamp(data ? c[k] : linearToSrgb(c[k]), 0.0f, 1.0f)));
    }
  std::vector<uint8_t> png;
  if (!stbi_write_png_to_func(appendBytes, &png, tex.width, tex.height, 3, rgb.data(), tex.width * 3))
    throw Error(fmt::format("cannot encode texture '{}' as PNG", tex.path));
  return png;
}

int addImage(tinygltf::Model& model, const std::string& name, const std::vector<uint8_t>& png, int sampler = 0) {
  tinygltf::Image image;
  image.name = name;
  image.mimeType = "image/png";
  image.bufferView = addBufferView(model, png.data(), png.size(), 0);
  model.bufferViews.back().target = 0;  // images are no vertex data
  model.images.push_back(image);
  tinygltf::Texture texture;
  texture.source = int(model.images.size()) - 1;
  texture.sampler = sampler;
  model.textures.push_back(texture);
  return int(model.textures.size()) - 1;
}

// A vertex's position, normal, uvs, colour and tangent: vertices equal in all of them are shared.
constexpr size_t kVertexKey = 17;

struct VertexKeyHash {
  size_t operator()(const std::array<float, kVertexKey>& k) const {
    size_t h = 1469598103934665603ull;
    for (float f : k) {
      uint32_t bits;
      std::memcpy(&bits, &f, 4);
      h = (h ^ bits) * 1099511628211ull;
    }
    return h;
  }
};

void checkOptions(const Scene& scene, const GlbOptions& o) {
  // `perMesh`: a mesh's own list may be empty (the attribute is left off that mesh).
  auto check = [&](size_t outer, auto inner, const char* what, size_t perFace, bool perMesh) {
    if (outer == 0) return;
    if (outer != scene.meshes.size())
      throw Error(fmt::format("glb: {} for {} meshes, the scene has {}", what, outer, scene.meshes.size()));
    for (size_t m = 0; m < scene.meshes.size(); ++m)
      if (inner(m) != scene.meshes[m].faces.size() * perFace && !(perMesh && inner(m) == 0))
        throw Error(fmt::format("glb: mesh '{}': {} has {} entries, expected {}", scene.meshes[m].name, what,
                                inner(m), scene.meshes[m].faces.size() * perFace));
  };
  check(o.vertexColors.size(), [&](size_t m) { return o.vertexColors[m].size(); }, "vertex colours", 4, true);
  check(o.secondUvs.size(), [&](size_t m) { return o.secondUvs[m].size(); }, "second uvs", 4, true);
  check(o.flippedFaces.size(), [&](size_t m) { return o.flippedFaces[m].size(); }, "flipped-face flags", 1, false);
  check(o.faceLightmap.size(), [&](size_t m) { return o.faceLightmap[m].size(); }, "face lightmaps", 1, true);
  if (!o.directionalMode.empty()) {
    if (o.directionalImages.size() != o.images.size())
      throw Error(fmt::format("glb: {} direction-texture lists for {} images", o.directionalImages.size(), o.images.size()));
    for (const auto& list : o.directionalImages)
      for (int32_t i : list)
        if (i < 0 || i >= int32_t(o.images.size())) throw Error(fmt::format("glb: direction image {} does not exist", i));
  }
  if (o.transferBands > 0) {
    if (o.transferBands < 2 || o.transferBands > 4 || o.transferImages.size() != o.images.size() ||
        o.transferRatioScales.size() != o.images.size() ||
        o.transferSky.size() != size_t(o.transferBands * o.transferBands))
      throw Error(fmt::format("glb: a {}-band transfer with {} image lists for {} images and {} sky coefficients",
                              o.transferBands, o.transferImages.size(), o.images.size(), o.transferSky.size()));
    for (const auto& list : o.transferImages)
      for (int32_t i : list)
        if (i < 0 || i >= int32_t(o.images.size())) throw Error(fmt::format("glb: transfer image {} does not exist", i));
  }
  if (!o.faceLightmap.empty()) {
    for (size_t m = 0; m < scene.meshes.size(); ++m)
      if (!o.faceLightmap[m].empty() && (o.secondUvs.empty() || o.secondUvs[m].empty()))
        throw Error(fmt::format("glb: mesh '{}': lightmaps need second uvs (TEXCOORD_1)", scene.meshes[m].name));
    for (const auto& mesh : o.faceLightmap)
      for (int32_t i : mesh)
        if (i < -1 || i >= int32_t(o.images.size())) throw Error(fmt::format("glb: lightmap image {} does not exist", i));
  }
  if (o.elements) {
    if (!o.vertexColors.empty() || !o.secondUvs.empty())
      throw Error("glb: element tessellation excludes per-face-corner colours and second uvs");
    if (o.elementColors.size() != o.elements->elements.size() * 4)
      throw Error(fmt::format("glb: {} element colours for {} elements, expected 4 each", o.elementColors.size(),
                              o.elements->elements.size()));
    for (const SurfaceFace& f : o.elements->faces)
      if (f.mesh >= scene.meshes.size()) throw Error("glb: the elements come from another scene");
  }
  if (!o.elementDirections.empty() || !o.vertexDirections.empty() || !o.vertexDirectionalMode.empty()) {
    if (!o.elements && o.vertexColors.empty())
      throw Error("glb: directions per vertex need vertex colours (the element tessellation's or the meshes')");
    const int textures = directionalTextureCount(parseDirectionalMode(o.vertexDirectionalMode));
    const size_t given = o.elements ? o.elementDirections.size() : o.vertexDirections.size();
    if (textures == 0 || int(given) != textures || (o.elements && !o.vertexDirections.empty()))
      throw Error(fmt::format("glb: {} direction lists for mode '{}', expected {}", given, o.vertexDirectionalMode,
                              textures));
    for (const FaceCornerValues& list : o.vertexDirections) {  // one per coloured corner
      if (list.size() != o.vertexColors.size())
        throw Error(fmt::format("glb: vertex directions for {} meshes, the scene has {}", list.size(), scene.meshes.size()));
      for (size_t m = 0; m < list.size(); ++m)
        if (list[m].size() != o.vertexColors[m].size())
          throw Error(fmt::format("glb: mesh '{}': {} vertex directions for {} vertex colours", scene.meshes[m].name,
                                  list[m].size(), o.vertexColors[m].size()));
    }
    for (const auto& list : o.elementDirections)
      if (list.size() != o.elements->elements.size() * 4)
        throw Error(fmt::format("glb: {} element directions for {} elements, expected 4 each", list.size(),
                                o.elements->elements.size()));
  }
}

void addMaterials(const Scene& scene, tinygltf::Model& model) {
  std::vector<int> textureOf(scene.textures.size(), -1), dataTextureOf(scene.textures.size(), -1);
  auto textureFor = [&](int t, bool data = false) {
    if (t < 0 || size_t(t) >= scene.textures.size()) return -1;
    int& slot = (data ? dataTextureOf : textureOf)[size_t(t)];
    if (slot < 0) slot = addImage(model, fmt::format("texture{}", t), encodeTexture(scene.textures[size_t(t)], data));
    return slot;
  };
  for (const Material& m : scene.materials) {
    tinygltf::Material g;
    g.name = m.name;
    g.pbrMetallicRoughness.baseColorFactor = {m.reflectance.r, m.reflectance.g, m.reflectance.b, 1.0};
    g.pbrMetallicRoughness.metallicFactor = 0.0;
    g.pbrMetallicRoughness.roughnessFactor = 1.0;
    g.pbrMetallicRoughness.baseColorTexture.index = textureFor(m.reflectanceTexture);
    const float peak = std::max({m.emission.r, m.emission.g, m.emission.b});
    if (peak > 0.0f) {
      const float scale = std::max(peak, 1.0f);
      g.emissiveFactor = {m.emission.r / scale, m.emission.g / scale, m.emission.b / scale};
      if (peak > 1.0f) {
        tinygltf::Value::Object strength;
        strength["emissiveStrength"] = tinygltf::Value(double(peak));
        g.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(strength);
      }
      g.emissiveTexture.index = textureFor(m.emissionTexture);
    }
    if (m.normalTexture >= 0) {
      g.normalTexture.index = textureFor(m.normalTexture, /*data=*/true);
      g.normalTexture.scale = m.normalScale;
    }
    g.doubleSided = m.twoSided;
    model.materials.push_back(g);
  }
  bool strength = false;
  for (const auto& g : model.materials) strength |= g.extensions.count("KHR_materials_emissive_strength") > 0;
  if (strength) model.extensionsUsed.push_back("KHR_materials_emissive_strength");
}

// A node's rotation that turns glTF's camera (looking down -z, +y up) to look from eye to target.
std::vector<double> cameraRotation(const Camera& c) {
  const Vec3 f = glm::normalize(c.target - c.eye);
  Vec3 r = glm::cross(f, c.up);
  if (glm::length(r) < 1e-6f) r = glm::cross(f, std::abs(f.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0));
  r = glm::normalize(r);
  const Vec3 u = glm::cross(r, f);
  const glm::quat q = glm::normalize(glm::quat_cast(glm::mat3(r, u, -f)));
  return {q.x, q.y, q.z, q.w};
}

// COLOR_0 must lie in [0,1] (the validator's ACCESSOR_NON_CLAMPED): values are divided by the
// smallest power of two at or above their largest component, which is exact in floating point.
float vertexColorScale(const GlbOptions& o) {
  float peak = 0.0f;
  auto visit = [&](const std::vector<Rgb>& colors) {
    for (const Rgb& c : colors) {
      if (!(std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b)) || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f)
        throw Error("glb: vertex colours must be finite and non-negative");
      peak = std::max({peak, c.r, c.g, c.b});
    }
  };
  for (const auto& mesh : o.vertexColors) visit(mesh);
  visit(o.elementColors);
  return peak > 1.0f ? std::exp2(std::ceil(std::log2(peak))) : 1.0f;
}

// Collects a mesh's vertices, merging exact duplicates, and its triangles.
// glTF's TANGENT of a face side with unit normal `normal`: the normal map's frame as luxel shades
// with it (render/normal_map.h). glTF's bitangent is cross(normal, tangent) * w, and both point
// along the image's up (luxel's +v). Degenerate uvs: any unit tangent (the map means nothing there).
glm::vec4 gltfTangent(const Mesh& mesh, uint32_t face, Vec3 normal) {
  const TangentFrame frame = faceTangentFrame(mesh, face, normal);
  if (frame.valid) return glm::vec4(frame.t, glm::dot(glm::cross(normal, frame.t), frame.b) >= 0.0f ? 1.0f : -1.0f);
  const Vec3 a = std::abs(normal.x) > 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
  return glm::vec4(glm::normalize(glm::cross(a, normal)), 1.0f);
}

struct MeshBuilder {
  bool hasUv = false, hasUv1 = false, hasColor = false, hasTangent = false;
  std::vector<std::array<float, 3>> positions, normals, colors;
  std::vector<std::array<float, 2>> uv0, uv1;
  std::vector<std::array<float, 4>> tangents;
  // Per direction attribute (_LUXEL_DIRECTIONk), per vertex. Not in the key: element corners with
  // the same position, normal and colour come from one smooth corner value (elementCornerValues),
  // whose directions are the same too.
  std::vector<std::vector<std::array<float, 3>>> directions;
  std::vector<uint32_t> indices;
  std::unordered_map<std::array<float, kVertexKey>, uint32_t, VertexKeyHash> seen;

  uint32_t vertex(Vec3 p, Vec3 n, Vec2 t0, Vec2 t1, Rgb c, glm::vec4 tangent = glm::vec4(0.0f),
                  const Rgb* direction = nullptr) {
    // glTF's v runs down the image; luxel's (like OpenGL's) runs up.
    const std::array<float, kVertexKey> key{p.x, p.y, p.z, n.x, n.y, n.z, t0.x, 1.0f - t0.y, t1.x, 1.0f - t1.y,
                                            c.r, c.g, c.b, tangent.x, tangent.y, tangent.z, tangent.w};
    auto [it, added] = seen.try_emplace(key, uint32_t(positions.size()));
    if (added) {
      positions.push_back({p.x, p.y, p.z});
      normals.push_back({n.x, n.y, n.z});
      if (hasUv) uv0.push_back({key[6], key[7]});
      if (hasUv1) uv1.push_back({key[8], key[9]});
      if (hasColor) colors.push_back({c.r, c.g, c.b});
      if (hasTangent) tangents.push_back({tangent.x, tangent.y, tangent.z, tangent.w});
      for (size_t k = 0; k < directions.size(); ++k) directions[k].push_back({direction[k].r, direction[k].g, direction[k].b});
    }
    return it->second;
  }
  // A triangle or quad (along its 0-2 diagonal, as discretisation cuts non-planar ones).
  void polygon(const uint32_t* corner, int n, bool reversed) {
    const int tris[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int t = 0; t < n - 2; ++t) {
      const auto& k = tris[t];
      if (reversed) indices.insert(indices.end(), {corner[k[0]], corner[k[2]], corner[k[1]]});
      else indices.insert(indices.end(), {corner[k[0]], corner[k[1]], corner[k[2]]});
    }
  }
};

// The element tessellation's layout: per mesh, its front-side surface faces; per surface face, its elements.
struct ElementIndex {
  std::vector<std::vector<uint32_t>> facesOfMesh;
  std::vector<std::vector<uint32_t>> elementsOfFace;
};

ElementIndex indexElements(const Scene& scene, const SurfaceSet& set) {
  ElementIndex index;
  index.facesOfMesh.resize(scene.meshes.size());
  index.elementsOfFace.resize(set.faces.size());
  for (uint32_t fi = 0; fi < set.faces.size(); ++fi) {
    const SurfaceFace& f = set.faces[fi];
    if (f.twin >= 0 && uint32_t(f.twin) < fi) continue;  // the back of a two-sided face
    index.facesOfMesh[f.mesh].push_back(fi);
  }
  for (uint32_t e = 0; e < set.elements.size(); ++e) index.elementsOfFace[set.elements[e].face].push_back(e);
  return index;
}

template <class Keep>
void addFaces(const Mesh& mesh, size_t mi, const GlbOptions& o, float colorScale, MeshBuilder& b, Keep keep);
tinygltf::Primitive makePrimitive(tinygltf::Model& model, MeshBuilder& b, int material);
void addVertexDirections(tinygltf::Model& model, const MeshBuilder& b, const std::string& mode, tinygltf::Primitive& prim);

// Lightmap pages: image index -> texture index and RGBM range; (material, page) -> material copy.
constexpr const char* kDirectionalExtension = "LUXEL_lightmap_directional";
constexpr const char* kVertexDirectionalExtension = "LUXEL_vertex_directional";
constexpr const char* kTransferExtension = "LUXEL_lightmap_transfer";

struct LightmapTextures {
  std::vector<int> texture;
  std::vector<float> range;
  const GlbOptions* options = nullptr;  // the direction and transfer textures, and the transfer's light
  std::map<std::pair<uint32_t, int32_t>, int> copies;
};

int lightmapMaterial(tinygltf::Model& model, LightmapTextures& lightmaps, uint32_t material, int32_t page) {
  auto [it, added] = lightmaps.copies.try_emplace({material, page}, int(model.materials.size()));
  if (added) {
    tinygltf::Material g = model.materials[material];
    g.name = fmt::format("{}@lightmap{}", g.name, page);
    tinygltf::Value::Object info;
    info["lightMap"] = tinygltf::Value(lightmaps.texture[size_t(page)]);
    info["lightMapTexCoord"] = tinygltf::Value(1);
    info["lightMapEncoding"] = tinygltf::Value(std::string("RGBM"));
    info["rgbmRange"] = tinygltf::Value(double(lightmaps.range[size_t(page)]));
    info["lightMapQuantity"] = tinygltf::Value(std::string("irradiance"));
    tinygltf::Value::Object extras;
    extras["luxel"] = tinygltf::Value(info);
    g.extras = tinygltf::Value(extras);
    const GlbOptions& o = *lightmaps.options;
    // A texture of `o.images` read through the lightmap's UVs.
    auto textureInfo = [&](int32_t image) {
      tinygltf::Value::Object t;
      t["index"] = tinygltf::Value(lightmaps.texture[size_t(image)]);
      t["texCoord"] = tinygltf::Value(1);
      return t;
    };
    if (!o.directionalMode.empty() && size_t(page) < o.directionalImages.size() && !o.directionalImages[size_t(page)].empty()) {
      tinygltf::Value::Array textures;
      for (int32_t image : o.directionalImages[size_t(page)]) textures.push_back(tinygltf::Value(textureInfo(image)));
      tinygltf::Value::Object ext;
      ext["mode"] = tinygltf::Value(o.directionalMode);
      ext["textures"] = tinygltf::Value(textures);
      g.extensions[kDirectionalExtension] = tinygltf::Value(ext);
    }
    if (o.transferBands > 0 && size_t(page) < o.transferImages.size() && !o.transferImages[size_t(page)].empty()) {
      const auto& images = o.transferImages[size_t(page)];
      auto rgb = [](Rgb c) {
        return tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(double(c.r)), tinygltf::Value(double(c.g)),
                                                      tinygltf::Value(double(c.b))});
      };
      tinygltf::Value::Object band0 = textureInfo(images[0]);
      band0["rgbmRange"] = tinygltf::Value(double(lightmaps.range[size_t(images[0])]));
      tinygltf::Value::Array ratios, sky, suns;
      for (size_t k = 1; k < images.size(); ++k) ratios.push_back(tinygltf::Value(textureInfo(images[k])));
      for (const Rgb& c : o.transferSky) sky.push_back(rgb(c));
      for (const GlbOptions::Sun& sun : o.transferSuns) {
        tinygltf::Value::Object v;
        v["direction"] = rgb(sun.direction);
        v["irradiance"] = rgb(sun.irradiance);
        suns.push_back(tinygltf::Value(v));
      }
      tinygltf::Value::Object ext;
      ext["bands"] = tinygltf::Value(o.transferBands);
      ext["band0"] = tinygltf::Value(band0);
      ext["ratios"] = tinygltf::Value(ratios);
      tinygltf::Value::Array scales;
      for (float v : o.transferRatioScales[size_t(page)]) scales.push_back(tinygltf::Value(double(v)));
      ext["ratioScale"] = tinygltf::Value(scales);
      ext["sky"] = tinygltf::Value(sky);
      ext["suns"] = tinygltf::Value(suns);
      g.extensions[kTransferExtension] = tinygltf::Value(ext);
    }
    model.materials.push_back(g);
  }
  return it->second;
}

void addMesh(const Scene& scene, size_t mi, const GlbOptions& o, float colorScale, const ElementIndex& index,
             LightmapTextures& lightmaps, tinygltf::Model& model) {
  const Mesh& mesh = scene.meshes[mi];
  MeshBuilder b;
  b.hasUv = !mesh.uvs.empty();
  b.hasUv1 = !o.secondUvs.empty() && !o.secondUvs[mi].empty();
  // Normal-mapped meshes carry their tangent frames (glTF would otherwise leave them to the viewer).
  b.hasTangent = b.hasUv && scene.materials[mesh.material].normalTexture >= 0;
  b.hasColor = (!o.vertexColors.empty() && !o.vertexColors[mi].empty()) || o.elements;
  tinygltf::Mesh gm;
  gm.name = mesh.name;

  if (o.elements) {
    const SurfaceSet& set = *o.elements;
    b.directions.resize(o.elementDirections.size());
    for (uint32_t fi : index.facesOfMesh[mi]) {
      const SurfaceFace& f = set.faces[fi];
      const glm::vec4 tangent = b.hasTangent ? gltfTangent(mesh, f.meshFace, f.normal) : glm::vec4(0.0f);
      for (uint32_t e : index.elementsOfFace[fi]) {
        const Element& el = set.elements[e];
        uint32_t corner[4];
        for (int c = 0; c < el.polygon.count; ++c) {
          Rgb direction[kMaxDirectionalCoefficients];
          for (size_t k = 0; k < o.elementDirections.size(); ++k)
            direction[k] = o.elementDirections[k][size_t(e) * 4 + size_t(c)];
          corner[c] = b.vertex(el.polygon.v[size_t(c)], f.normal, b.hasUv ? f.uv(el.param[size_t(c)]) : Vec2(0.0f),
                               Vec2(0.0f), o.elementColors[size_t(e) * 4 + size_t(c)] / colorScale, tangent, direction);
        }
        b.polygon(corner, el.polygon.count, false);
      }
    }
  } else if (!o.faceLightmap.empty() && !o.faceLightmap[mi].empty()) {
    // One primitive per lightmap page, each with its material's copy for that page.
    std::vector<int32_t> pages(o.faceLightmap[mi].begin(), o.faceLightmap[mi].end());
    std::sort(pages.begin(), pages.end());
    pages.erase(std::unique(pages.begin(), pages.end()), pages.end());
    for (int32_t page : pages) {
      MeshBuilder pb;
      pb.hasUv = b.hasUv, pb.hasUv1 = b.hasUv1, pb.hasColor = b.hasColor, pb.hasTangent = b.hasTangent;
      addFaces(mesh, mi, o, colorScale, pb, [&](size_t fi) { return o.faceLightmap[mi][fi] == page; });
      if (pb.indices.empty()) continue;
      gm.primitives.push_back(
          makePrimitive(model, pb, page < 0 ? int(mesh.material) : lightmapMaterial(model, lightmaps, mesh.material, page)));
    }
  } else {
    if (b.hasColor && !o.vertexDirections.empty()) b.directions.resize(o.vertexDirections.size());
    addFaces(mesh, mi, o, colorScale, b, [](size_t) { return true; });
  }
  if (!b.indices.empty()) {
    gm.primitives.push_back(makePrimitive(model, b, int(mesh.material)));
    if (!b.directions.empty()) addVertexDirections(model, b, o.vertexDirectionalMode, gm.primitives.back());
  }
  if (gm.primitives.empty()) return;  // a mesh without faces: glTF meshes need a primitive
  model.meshes.push_back(gm);
  tinygltf::Node node;
  node.name = mesh.name;
  node.mesh = int(model.meshes.size()) - 1;
  model.nodes.push_back(node);
  model.scenes[0].nodes.push_back(int(model.nodes.size()) - 1);
}

template <class Keep>
void addFaces(const Mesh& mesh, size_t mi, const GlbOptions& o, float colorScale, MeshBuilder& b, Keep keep) {
  {
    for (size_t fi = 0; fi < mesh.faces.size(); ++fi) {
      if (!keep(fi)) continue;
      const Face& face = mesh.faces[fi];
      const int n = face.vertexCount();
      const bool flipped = !o.flippedFaces.empty() && o.flippedFaces[mi][fi];
      Polygon poly;
      poly.count = n;
      for (int k = 0; k < n; ++k) poly.v[size_t(k)] = mesh.positions[face.v[size_t(k)]];
      Vec3 normal = poly.normal();
      if (normal == Vec3(0.0f)) normal = Vec3(0.0f, 0.0f, 1.0f);  // degenerate: any unit vector
      if (flipped) normal = -normal;
      const glm::vec4 tangent = b.hasTangent ? gltfTangent(mesh, uint32_t(fi), normal) : glm::vec4(0.0f);
      uint32_t corner[4];
      for (int k = 0; k < n; ++k) {
        const size_t fc = fi * 4 + size_t(k);
        Rgb direction[kMaxDirectionalCoefficients];
        for (size_t t = 0; t < b.directions.size(); ++t) direction[t] = o.vertexDirections[t][mi][fc];
        corner[k] = b.vertex(poly.v[size_t(k)], normal, b.hasUv ? mesh.uvs[face.v[size_t(k)]] : Vec2(0.0f),
                             b.hasUv1 ? o.secondUvs[mi][fc] : Vec2(0.0f),
                             b.hasColor ? o.vertexColors[mi][fc] / colorScale : Rgb(0.0f), tangent, direction);
      }
      b.polygon(corner, n, flipped);
    }
  }
}

// The per-vertex directions as attributes _LUXEL_DIRECTIONk, named by the primitive's
// LUXEL_vertex_directional extension (docs/schema/LUXEL_vertex_directional.schema.json).
void addVertexDirections(tinygltf::Model& model, const MeshBuilder& b, const std::string& mode, tinygltf::Primitive& prim) {
  tinygltf::Value::Array names;
  for (size_t k = 0; k < b.directions.size(); ++k) {
    const std::string name = fmt::format("_LUXEL_DIRECTION{}", k);
    prim.attributes[name] = addFloatAccessor<3>(model, b.directions[k], TINYGLTF_TYPE_VEC3, false);
    names.push_back(tinygltf::Value(name));
  }
  tinygltf::Value::Object ext;
  ext["mode"] = tinygltf::Value(mode);
  ext["attributes"] = tinygltf::Value(names);
  prim.extensions[kVertexDirectionalExtension] = tinygltf::Value(ext);
}

tinygltf::Primitive makePrimitive(tinygltf::Model& model, MeshBuilder& b, int material) {
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = material;
  prim.attributes["POSITION"] = addFloatAccessor<3>(model, b.positions, TINYGLTF_TYPE_VEC3, true);
  prim.attributes["NORMAL"] = addFloatAccessor<3>(model, b.normals, TINYGLTF_TYPE_VEC3, false);
  if (b.hasUv1) {
    const int uv1 = addFloatAccessor<2>(model, b.uv1, TINYGLTF_TYPE_VEC2, false);
    prim.attributes["TEXCOORD_1"] = uv1;
    // glTF numbers each semantic's sets from 0 without gaps: a mesh without its own uvs shares the
    // lightmap's accessor as TEXCOORD_0, which no texture of its material reads.
    prim.attributes["TEXCOORD_0"] = b.hasUv ? addFloatAccessor<2>(model, b.uv0, TINYGLTF_TYPE_VEC2, false) : uv1;
  } else if (b.hasUv) {
    prim.attributes["TEXCOORD_0"] = addFloatAccessor<2>(model, b.uv0, TINYGLTF_TYPE_VEC2, false);
  }
  if (b.hasColor) prim.attributes["COLOR_0"] = addFloatAccessor<3>(model, b.colors, TINYGLTF_TYPE_VEC3, false);
  if (b.hasTangent) prim.attributes["TANGENT"] = addFloatAccessor<4>(model, b.tangents, TINYGLTF_TYPE_VEC4, false);
  prim.indices = addIndexAccessor(model, b.indices, b.positions.size());
  return prim;
}

}  // namespace

namespace {

// Materials no primitive uses (the scene's originals once every mesh took a lightmap copy, or
// materials of no face) are left out, so that a validator sees no unused objects.
void dropUnusedMaterials(tinygltf::Model& model) {
  std::vector<int> newIndex(model.materials.size(), -1);
  for (const tinygltf::Mesh& m : model.meshes)
    for (const tinygltf::Primitive& p : m.primitives)
      if (p.material >= 0) newIndex[size_t(p.material)] = 0;
  std::vector<tinygltf::Material> kept;
  for (size_t i = 0; i < model.materials.size(); ++i)
    if (newIndex[i] == 0) newIndex[i] = int(kept.size()), kept.push_back(std::move(model.materials[i]));
  model.materials = std::move(kept);
  for (tinygltf::Mesh& m : model.meshes)
    for (tinygltf::Primitive& p : m.primitives)
      if (p.material >= 0) p.material = newIndex[size_t(p.material)];
  bool strength = false;
  for (const auto& g : model.materials) strength |= g.extensions.count("KHR_materials_emissive_strength") > 0;
  if (!strength) std::erase(model.extensionsUsed, std::string("KHR_materials_emissive_strength"));
}

}  // namespace

void writeGlb(const Scene& scene, const std::filesystem::path& path, const GlbOptions& options) {
  checkOptions(scene, options);
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = options.generator;
  model.buffers.resize(1);
  model.scenes.resize(1);
  model.scenes[0].name = scene.name;
  model.defaultScene = 0;
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  sampler.wrapS = sampler.wrapT = TINYGLTF_TEXTURE_WRAP_REPEAT;
  model.samplers.push_back(sampler);

  addMaterials(scene, model);
  LightmapTextures lightmaps;
  for (const GlbImage& image : options.images) {
    int sampler = 0;
    if (image.rgbmRange > 0.0f || image.clamped) {  // lightmaps: no mipmaps (they would blend charts), clamped
      if (model.samplers.size() < 2) {
        tinygltf::Sampler s;
        s.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
        s.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
        s.wrapS = s.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
        model.samplers.push_back(s);
      }
      sampler = 1;
    }
    lightmaps.texture.push_back(addImage(model, image.name, image.png, sampler));
    lightmaps.range.push_back(image.rgbmRange);
  }
  lightmaps.options = &options;
  const float colorScale = vertexColorScale(options);
  const ElementIndex index = options.elements ? indexElements(scene, *options.elements) : ElementIndex{};
  for (size_t m = 0; m < scene.meshes.size(); ++m) addMesh(scene, m, options, colorScale, index, lightmaps, model);
  // Our extensions are declared where something carries them: a bake whose meshes all took vertex
  // colours has no lightmap material to extend.
  auto materialsUse = [&](const char* name) {
    return std::any_of(model.materials.begin(), model.materials.end(), [&](auto& m) { return m.extensions.count(name) > 0; });
  };
  auto primitivesUse = [&](const char* name) {
    return std::any_of(model.meshes.begin(), model.meshes.end(), [&](auto& m) {
      return std::any_of(m.primitives.begin(), m.primitives.end(), [&](auto& p) { return p.extensions.count(name) > 0; });
    });
  };
  for (const char* name : {kTransferExtension, kDirectionalExtension})
    if (materialsUse(name)) model.extensionsUsed.push_back(name);
  if (primitivesUse(kVertexDirectionalExtension)) model.extensionsUsed.push_back(kVertexDirectionalExtension);
  const bool anyColors = std::any_of(options.vertexColors.begin(), options.vertexColors.end(),
                                     [](const std::vector<Rgb>& mesh) { return !mesh.empty(); });
  if (anyColors || options.elements) {
    // What COLOR_0 holds and the factor that turns it back into that quantity (docs/baking.md);
    // three.js puts scene extras in gltf.scene.userData.
    tinygltf::Value::Object info;
    info["vertexColors"] = tinygltf::Value(options.vertexColorQuantity);
    info["vertexColorScale"] = tinygltf::Value(double(colorScale));
    tinygltf::Value::Object extras;
    extras["luxel"] = tinygltf::Value(info);
    model.scenes[0].extras = tinygltf::Value(extras);
  }
  if (model.meshes.empty()) throw Error(fmt::format("{}: scene '{}' has no faces to write", path.string(), scene.name));
  dropUnusedMaterials(model);

  // Cameras, sized to the scene: clip planes at a thousandth and a hundred times its extent
  // (tinygltf always writes zfar, so it cannot be left infinite).
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const Mesh& m : scene.meshes)
    for (const Vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double extent = std::max(double(glm::length(hi - lo)), 1e-6);
  for (const Camera& c : scene.cameras) {
    if (glm::length(c.target - c.eye) <= 0.0f) continue;
    tinygltf::Camera gc;
    gc.name = c.name;
    gc.type = "perspective";
    gc.perspective.yfov = glm::radians(double(c.fovY));
    gc.perspective.znear = 1e-3 * extent;
    gc.perspective.zfar = 100.0 * extent;
    model.cameras.push_back(gc);
    tinygltf::Node node;
    node.name = c.name;
    node.camera = int(model.cameras.size()) - 1;
    node.translation = {c.eye.x, c.eye.y, c.eye.z};
    node.rotation = cameraRotation(c);
    model.nodes.push_back(node);
    model.scenes[0].nodes.push_back(int(model.nodes.size()) - 1);
  }
  if (model.samplers.size() == 1 && model.textures.empty()) model.samplers.clear();

  std::ostringstream glb(std::ios::binary);
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, glb, false, true)) throw Error(fmt::format("{}: cannot encode the glb", path.string()));
  writeTextAtomically(path, glb.view());
}

}  // namespace luxel
