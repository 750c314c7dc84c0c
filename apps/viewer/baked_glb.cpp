#include "baked_glb.h"

#include <cmath>
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

// Reads one material's LUXEL_lightmap_transfer into `out` and `light`, checking it against the
// schema (docs/schema/LUXEL_lightmap_transfer.schema.json) and what the viewer can draw: every
// mistake names the file, the material and what is wrong.
struct TransferReader {
  const tinygltf::Model& model;
  const BakedGlb& glb;
  std::string at;  // "FILE: material N ('NAME'): LUXEL_lightmap_transfer"

  [[noreturn]] void fail(const std::string& what) const { throw Error(fmt::format("{}: {}", at, what)); }

  double finite(const tinygltf::Value& v, const std::string& what) const {
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) fail(what + " is not a finite number");
    return v.GetNumberAsDouble();
  }
  Vec3 triple(const tinygltf::Value& v, const std::string& what) const {
    if (!v.IsArray() || v.ArrayLen() != 3) fail(what + " is not an array of 3 numbers");
    return Vec3(float(finite(v.Get(0), what + "[0]")), float(finite(v.Get(1), what + "[1]")), float(finite(v.Get(2), what + "[2]")));
  }
  // A texture read on TEXCOORD_1 (the lightmap's), decoded, as an image index.
  int image(const tinygltf::Value& info, const std::string& what) const {
    if (!info.IsObject() || !info.Has("index")) fail(what + " is not a texture reference with an index");
    const double index = finite(info.Get("index"), what + ".index");
    if (index < 0 || index != std::floor(index) || size_t(index) >= model.textures.size())
      fail(fmt::format("{}.index {} is not one of the file's {} textures", what, index, model.textures.size()));
    const int source = model.textures[size_t(index)].source;
    if (source < 0 || size_t(source) >= glb.images.size() || glb.images[size_t(source)].width <= 0)
      fail(fmt::format("{}: texture {} has no 8-bit image the viewer could decode", what, index));
    if (info.Has("texCoord") && finite(info.Get("texCoord"), what + ".texCoord") != 1.0)
      fail(fmt::format("{}.texCoord is {}: transfer pages are read on the lightmap's TEXCOORD_1", what,
                       number(info.Get("texCoord"))));
    return source;
  }

  void read(const tinygltf::Value& ext, BakedGlb::Material& out, BakedGlb::TransferLight& light) const {
    if (!ext.IsObject()) fail("is not an object");
    for (const char* key : {"bands", "band0", "ratios", "ratioScale", "sky", "suns"})
      if (!ext.Has(key)) fail(fmt::format("has no '{}'", key));
    const double bands = finite(ext.Get("bands"), "bands");
    if (bands != std::floor(bands) || bands < 2 || bands > 4) fail(fmt::format("bands is {}, not 2, 3 or 4", bands));
    out.transferBands = light.bands = int(bands);
    const size_t n = size_t(bands * bands);

    const tinygltf::Value& band0 = ext.Get("band0");
    out.transferBand0 = image(band0, "band0");
    const double range = band0.Has("rgbmRange") ? finite(band0.Get("rgbmRange"), "band0.rgbmRange") : 0.0;
    if (!(range > 0.0)) fail("band0.rgbmRange is missing or not above 0");
    out.transferBand0Range = float(range);
    const BakedGlb::Image& page = glb.images[size_t(out.transferBand0)];

    const tinygltf::Value& ratios = ext.Get("ratios");
    const size_t textures = (3 * (n - 1) + 3) / 4;
    if (!ratios.IsArray() || ratios.ArrayLen() != textures)
      fail(fmt::format("ratios is not an array of {} textures ({} bands: {} numbers a texel, four a texture)", textures,
                       int(bands), 3 * (n - 1)));
    for (size_t k = 0; k < textures; ++k) {
      const int i = image(ratios.Get(int(k)), fmt::format("ratios[{}]", k));
      const BakedGlb::Image& r = glb.images[size_t(i)];
      if (r.width != page.width || r.height != page.height)
        fail(fmt::format("ratios[{}] is {}x{}, band0 {}x{}: a texel's numbers must lie at the same place", k, r.width,
                         r.height, page.width, page.height));
      out.transferRatios.push_back(i);
    }

    const tinygltf::Value& scale = ext.Get("ratioScale");
    if (!scale.IsArray() || scale.ArrayLen() != n - 1) fail(fmt::format("ratioScale is not an array of {} numbers", n - 1));
    for (size_t i = 0; i + 1 < n; ++i) {
      const double s = finite(scale.Get(int(i)), fmt::format("ratioScale[{}]", i));
      if (!(s > 0.0)) fail(fmt::format("ratioScale[{}] is {}, not above 0", i, s));
      out.ratioScale.push_back(float(s));
    }

    const tinygltf::Value& sky = ext.Get("sky");
    if (!sky.IsArray() || sky.ArrayLen() != n) fail(fmt::format("sky is not an array of {} RGB coefficients", n));
    light.sky.clear();
    for (size_t i = 0; i < n; ++i) light.sky.push_back(triple(sky.Get(int(i)), fmt::format("sky[{}]", i)));

    const tinygltf::Value& suns = ext.Get("suns");
    if (!suns.IsArray()) fail("suns is not an array");
    light.suns.clear();
    for (size_t i = 0; i < suns.ArrayLen(); ++i) {
      const tinygltf::Value& sun = suns.Get(int(i));
      const std::string what = fmt::format("suns[{}]", i);
      if (!sun.IsObject() || !sun.Has("direction") || !sun.Has("irradiance")) fail(what + " has no direction and irradiance");
      BakedGlb::TransferSun s;
      s.direction = triple(sun.Get("direction"), what + ".direction");
      if (!(glm::length(s.direction) > 0.0f)) fail(what + ".direction is zero");
      s.direction = glm::normalize(s.direction);
      s.irradiance = triple(sun.Get("irradiance"), what + ".irradiance");
      if (glm::any(glm::lessThan(s.irradiance, Rgb(0.0f)))) fail(what + ".irradiance is negative");
      light.suns.push_back(s);
    }
  }
};

bool sameLight(const BakedGlb::TransferLight& a, const BakedGlb::TransferLight& b) {
  if (a.bands != b.bands || a.sky != b.sky || a.suns.size() != b.suns.size()) return false;
  for (size_t i = 0; i < a.suns.size(); ++i)
    if (a.suns[i].direction != b.suns[i].direction || a.suns[i].irradiance != b.suns[i].irradiance) return false;
  return true;
}

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
  int firstTransfer = -1;  // the material whose light glb.transfer holds
  for (const tinygltf::Material& m : model.materials) {
    BakedGlb::Material out;
    const int index = int(glb.materials.size());
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
    if (auto it = m.extensions.find("LUXEL_lightmap_transfer"); it != m.extensions.end()) {
      const TransferReader reader{model, glb, fmt::format("{}: material {} ('{}'): LUXEL_lightmap_transfer", file, index, m.name)};
      BakedGlb::TransferLight light;
      reader.read(it->second, out, light);
      // One light relights every material: a file whose materials disagree cannot be shown as one.
      if (firstTransfer < 0) {
        glb.transfer = std::move(light);
        firstTransfer = index;
      } else if (!sameLight(light, glb.transfer)) {
        reader.fail(fmt::format("its bands, sky or suns differ from material {}'s (every transfer material holds the same light)",
                                firstTransfer));
      }
      glb.hasLightmaps = true;
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
      if (auto it = p.extensions.find("LUXEL_vertex_directional"); it != p.extensions.end()) {
        // Directions per vertex: the mode and the attributes that hold them, checked as the schema says.
        const tinygltf::Value& ext = it->second;
        const auto bad = [&](const std::string& what) {
          return Error(fmt::format("{}: mesh {}: LUXEL_vertex_directional {}", file, node.mesh, what));
        };
        if (!ext.IsObject() || !ext.Has("mode") || !ext.Get("mode").IsString() || !ext.Has("attributes") ||
            !ext.Get("attributes").IsArray())
          throw bad("needs a string 'mode' and an array 'attributes'");
        const std::string mode = ext.Get("mode").Get<std::string>();
        const size_t count = mode == "sh-l1" ? 3 : mode == "dominant" ? 1 : mode == "sh-l2" ? 8 : 0;
        if (count == 0) throw bad(fmt::format("mode '{}' is not sh-l1, sh-l2 or dominant", mode));
        const tinygltf::Value& names = ext.Get("attributes");
        if (names.ArrayLen() != count) throw bad(fmt::format("has {} attributes where {} needs {}", names.ArrayLen(), mode, count));
        out.directionalMode = mode;
        for (size_t k = 0; k < count; ++k) {
          const tinygltf::Value& name = names.Get(int(k));
          if (!name.IsString() || !p.attributes.count(name.Get<std::string>()))
            throw bad(fmt::format("attribute {} is not one of the primitive's", k));
          const std::string attribute = name.Get<std::string>();
          const std::vector<glm::vec3> values = read.floats<3>(p.attributes.at(attribute), attribute.c_str());
          if (out.directions.empty()) out.directions.assign(values.size(), {});
          if (values.size() != out.directions.size()) throw bad(fmt::format("attribute {} has another length", attribute));
          for (size_t v = 0; v < values.size(); ++v) out.directions[v][k] = values[v];
        }
      }
      const size_t n = out.positions.size();
      if ((!out.directions.empty() && out.directions.size() != n) ||
          (!out.uv0.empty() && out.uv0.size() != n) || (!out.uv1.empty() && out.uv1.size() != n) ||
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
