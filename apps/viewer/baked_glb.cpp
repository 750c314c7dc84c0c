#include "baked_glb.h"

#include <cstring>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "luxel/error.h"

namespace luxel::viewer {
namespace {

// Element `i` of accessor `a` as floats (float, or normalised integers as glTF allows for colours
// and texture coordinates), `n` components.
struct AccessorReader {
  const tinygltf::Model& model;
  const std::string& file;

  template <int N>
  std::vector<glm::vec<N, float>> floats(int accessor, const char* what) const {
    const tinygltf::Accessor& a = model.accessors.at(size_t(accessor));
    const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    if (components < N) throw Error(fmt::format("{}: {} has {} components, expected {}", file, what, components, N));
    const tinygltf::BufferView& v = model.bufferViews.at(size_t(a.bufferView));
    const tinygltf::Buffer& b = model.buffers.at(size_t(v.buffer));
    const int size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    const size_t stride = v.byteStride ? v.byteStride : size_t(components * size);
    const size_t start = v.byteOffset + a.byteOffset;
    if (a.count > 0 && start + stride * (a.count - 1) + size_t(components * size) > b.data.size())
      throw Error(fmt::format("{}: {} reads past its buffer", file, what));
    std::vector<glm::vec<N, float>> out(a.count);
    for (size_t i = 0; i < a.count; ++i) {
      const uint8_t* p = b.data.data() + start + stride * i;
      for (int c = 0; c < N; ++c) {
        float x = 0.0f;
        switch (a.componentType) {
          case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&x, p + c * 4, 4); break;
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: x = float(p[c]) / 255.0f; break;
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t u;
            std::memcpy(&u, p + c * 2, 2);
            x = float(u) / 65535.0f;
            break;
          }
          default: throw Error(fmt::format("{}: {} has component type {}, not float or normalised", file, what, a.componentType));
        }
        out[i][c] = x;
      }
    }
    return out;
  }

  std::vector<uint32_t> indices(int accessor, size_t vertexCount) const {
    const tinygltf::Accessor& a = model.accessors.at(size_t(accessor));
    const tinygltf::BufferView& v = model.bufferViews.at(size_t(a.bufferView));
    const tinygltf::Buffer& b = model.buffers.at(size_t(v.buffer));
    const int size = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    const size_t stride = v.byteStride ? v.byteStride : size_t(size);
    const size_t start = v.byteOffset + a.byteOffset;
    if (a.count > 0 && start + stride * (a.count - 1) + size_t(size) > b.data.size())
      throw Error(fmt::format("{}: indices read past their buffer", file));
    std::vector<uint32_t> out(a.count);
    for (size_t i = 0; i < a.count; ++i) {
      const uint8_t* p = b.data.data() + start + stride * i;
      uint32_t x = 0;
      if (size == 1) x = p[0];
      else if (size == 2) { uint16_t u; std::memcpy(&u, p, 2); x = u; }
      else std::memcpy(&x, p, 4);
      if (x >= vertexCount) throw Error(fmt::format("{}: index {} of {} vertices", file, x, vertexCount));
      out[i] = x;
    }
    return out;
  }
};

glm::mat4 nodeMatrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(n.matrix[size_t(i)]);
    return m;
  }
  glm::mat4 m(1.0f);
  if (n.translation.size() == 3) m = glm::translate(m, Vec3(float(n.translation[0]), float(n.translation[1]), float(n.translation[2])));
  if (n.rotation.size() == 4)
    m *= glm::mat4_cast(glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2])));
  if (n.scale.size() == 3) m = glm::scale(m, Vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2])));
  return m;
}

double number(const tinygltf::Value& v) { return v.IsNumber() ? v.GetNumberAsDouble() : 0.0; }

}  // namespace

BakedGlb readBakedGlb(const std::filesystem::path& path) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  const std::string file = path.string();
  const bool binary = path.extension() == ".glb";
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, file) : loader.LoadASCIIFromFile(&model, &err, &warn, file);
  if (!ok) throw Error(fmt::format("{}: cannot read it as glTF: {}", file, err.empty() ? warn : err));

  BakedGlb glb;
  float colorScale = 1.0f;
  const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
  if (size_t(sceneIndex) < model.scenes.size()) {
    const tinygltf::Value& luxel = model.scenes[size_t(sceneIndex)].extras.Get("luxel");
    if (luxel.IsObject()) {
      if (luxel.Has("vertexColors") && luxel.Get("vertexColors").IsString()) glb.vertexColors = luxel.Get("vertexColors").Get<std::string>();
      if (luxel.Has("vertexColorScale")) colorScale = float(number(luxel.Get("vertexColorScale")));
    }
  }
  for (const tinygltf::Image& im : model.images) {
    BakedGlb::Image out;
    if (im.component == 4 && im.bits == 8 && !im.image.empty()) {
      out.width = im.width, out.height = im.height, out.rgba = im.image;
    } else if (!im.image.empty() && im.bits == 8 && im.component >= 1 && im.component <= 4) {
      out.width = im.width, out.height = im.height;
      out.rgba.resize(size_t(im.width) * size_t(im.height) * 4, 255);
      for (size_t i = 0; i < size_t(im.width) * size_t(im.height); ++i)
        for (int c = 0; c < im.component; ++c) out.rgba[i * 4 + size_t(c)] = im.image[i * size_t(im.component) + size_t(c)];
    }
    glb.images.push_back(std::move(out));
  }
  auto imageOf = [&](int texture) {
    return texture >= 0 && size_t(texture) < model.textures.size() ? model.textures[size_t(texture)].source : -1;
  };
  for (const tinygltf::Material& m : model.materials) {
    BakedGlb::Material out;
    const auto& f = m.pbrMetallicRoughness.baseColorFactor;
    if (f.size() == 4) out.baseColor = glm::vec4(float(f[0]), float(f[1]), float(f[2]), float(f[3]));
    out.baseTexture = imageOf(m.pbrMetallicRoughness.baseColorTexture.index);
    if (m.emissiveFactor.size() == 3) out.emission = Rgb(float(m.emissiveFactor[0]), float(m.emissiveFactor[1]), float(m.emissiveFactor[2]));
    if (auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end() && it->second.Has("emissiveStrength"))
      out.emission *= float(number(it->second.Get("emissiveStrength")));
    const tinygltf::Value& luxel = m.extras.Get("luxel");
    if (luxel.IsObject() && luxel.Has("lightMap")) {
      out.lightmap = imageOf(int(number(luxel.Get("lightMap"))));
      out.rgbmRange = luxel.Has("rgbmRange") ? float(number(luxel.Get("rgbmRange"))) : 1.0f;
      glb.hasLightmaps = glb.hasLightmaps || out.lightmap >= 0;
    }
    out.doubleSided = m.doubleSided;
    out.normalTexture = imageOf(m.normalTexture.index);
    out.normalScale = float(m.normalTexture.scale);
    if (auto it = m.extensions.find("LUXEL_lightmap_directional"); it != m.extensions.end() && it->second.IsObject()) {
      const tinygltf::Value& ext = it->second;
      if (ext.Has("mode") && ext.Get("mode").IsString()) out.directionalMode = ext.Get("mode").Get<std::string>();
      const tinygltf::Value& textures = ext.Get("textures");
      if (textures.IsArray())
        for (size_t k = 0; k < textures.ArrayLen(); ++k) out.directionImages.push_back(imageOf(int(number(textures.Get(int(k)).Get("index")))));
    }
    glb.materials.push_back(out);
  }

  const AccessorReader read{model, file};
  // Every mesh node of the scene, with its world transform.
  std::vector<std::pair<int, glm::mat4>> stack;
  if (size_t(sceneIndex) < model.scenes.size())
    for (int n : model.scenes[size_t(sceneIndex)].nodes) stack.push_back({n, glm::mat4(1.0f)});
  size_t visited = 0;
  while (!stack.empty()) {
    auto [n, parent] = stack.back();
    stack.pop_back();
    if (n < 0 || size_t(n) >= model.nodes.size() || ++visited > 10 * model.nodes.size() + 10)
      throw Error(fmt::format("{}: the node hierarchy is broken (node {}, or a cycle)", file, n));
    const tinygltf::Node& node = model.nodes[size_t(n)];
    const glm::mat4 world = parent * nodeMatrix(node);
    for (int c : node.children) stack.push_back({c, world});
    if (node.mesh < 0 || size_t(node.mesh) >= model.meshes.size()) continue;
    for (const tinygltf::Primitive& p : model.meshes[size_t(node.mesh)].primitives) {
      if (p.mode != TINYGLTF_MODE_TRIANGLES || !p.attributes.count("POSITION")) continue;
      BakedGlb::Primitive out;
      for (const glm::vec3& v : read.floats<3>(p.attributes.at("POSITION"), "POSITION")) out.positions.push_back(Vec3(world * glm::vec4(v, 1.0f)));
      if (p.attributes.count("TEXCOORD_0")) out.uv0 = read.floats<2>(p.attributes.at("TEXCOORD_0"), "TEXCOORD_0");
      if (p.attributes.count("TEXCOORD_1")) out.uv1 = read.floats<2>(p.attributes.at("TEXCOORD_1"), "TEXCOORD_1");
      if (p.attributes.count("COLOR_0"))
        for (const glm::vec3& c : read.floats<3>(p.attributes.at("COLOR_0"), "COLOR_0")) out.colors.push_back(c * colorScale);
      const glm::mat3 linear(world), normalMatrix = glm::transpose(glm::inverse(linear));
      if (p.attributes.count("NORMAL"))
        for (const glm::vec3& v : read.floats<3>(p.attributes.at("NORMAL"), "NORMAL")) out.normals.push_back(glm::normalize(normalMatrix * v));
      if (p.attributes.count("TANGENT"))
        for (const glm::vec4& t : read.floats<4>(p.attributes.at("TANGENT"), "TANGENT"))
          out.tangents.push_back(glm::vec4(glm::normalize(linear * glm::vec3(t)), t.w < 0.0f ? -1.0f : 1.0f));
      if (p.indices >= 0) {
        out.indices = read.indices(p.indices, out.positions.size());
      } else {
        out.indices.resize(out.positions.size());
        for (uint32_t i = 0; i < out.indices.size(); ++i) out.indices[i] = i;
      }
      const size_t n = out.positions.size();
      if ((!out.uv0.empty() && out.uv0.size() != n) || (!out.uv1.empty() && out.uv1.size() != n) ||
          (!out.colors.empty() && out.colors.size() != n) || (!out.normals.empty() && out.normals.size() != n) ||
          (!out.tangents.empty() && out.tangents.size() != n))
        throw Error(fmt::format("{}: a primitive of mesh {} has attributes of different lengths", file, node.mesh));
      out.material = p.material >= 0 && size_t(p.material) < glb.materials.size() ? p.material : -1;
      glb.primitives.push_back(std::move(out));
    }
  }
  return glb;
}

}  // namespace luxel::viewer
