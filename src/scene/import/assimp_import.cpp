// Importing mesh files through Assimp (OBJ/MTL, glTF 2.0, FBX, PLY, COLLADA, ...): geometry with
// node transforms applied, diffuse materials, KHR_lights_punctual lights and cameras. Everything
// is read from the main file's bytes and a ResourceReader (assimp_io.h); importMeshFile only
// reads the file and points a FileResourceReader at its folder.
//
// We walk the node graph ourselves instead of using aiProcess_PreTransformVertices: that step
// double-translates glTF cameras in Assimp 5.2 (their importer copies the node translation into
// aiCamera::mPosition as well) and does not fix the winding of mirrored instances.
#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/ObjMaterial.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <span>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "luxel/resources.h"
#include "core/large_stack.h"
#include "io/input_file.h"
#include "scene/bump_map.h"
#include "scene/coincident_faces.h"
#include "scene/stray_geometry.h"
#include "scene/import/assimp_io.h"
#include "scene/import/child_process_import.h"
#include "scene/import/collada_indices.h"
#include "scene/import/gltf_accessors.h"
#include "scene/import/gltf_extras.h"
#include "scene/import/obj_references.h"
#include "scene/import/ply_header.h"
#include "scene/import/quads.h"
#include "scene/import/resource_path.h"
#include "scene/import/transform.h"
#include "scene/texture_decode.h"

namespace luxel {
namespace {

namespace fs = std::filesystem;

// Reflectance is kept below 1 so that every bounce loses energy and the solvers converge.
constexpr float kMaxReflectance = 0.99f;
constexpr float kPi = 3.14159265358979f;

enum class Format { Gltf, Collada, Fbx, Other };

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// From the name Assimp reads, whose extension chose the importer.
Format formatOf(const fs::path& path) {
  std::string ext = lower(path.extension().string());
  if (ext == ".gltf" || ext == ".glb") return Format::Gltf;
  if (ext == ".dae") return Format::Collada;
  if (ext == ".fbx") return Format::Fbx;
  return Format::Other;
}

glm::mat4 toGlm(const aiMatrix4x4& m) {
  // aiMatrix4x4 is row-major (a1..a4 is the first row); glm is column-major.
  glm::mat4 r;
  for (unsigned row = 0; row < 4; ++row)
    for (unsigned col = 0; col < 4; ++col) r[int(col)][int(row)] = m[row][col];
  return r;
}

glm::mat4 globalTransform(const aiNode* node) {
  glm::mat4 m(1.0f);
  for (; node; node = node->mParent) m = toGlm(node->mTransformation) * m;
  return m;
}

Vec3 toVec3(const aiVector3D& v) { return Vec3(v.x, v.y, v.z); }
bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Percent-decoding for glTF URIs ("my%20texture.png"); returns the input when it is not encoded.
std::string percentDecode(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit((unsigned char)s[i + 1]) &&
        std::isxdigit((unsigned char)s[i + 2])) {
      out += char(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

// Finds a texture the material refers to, as a path for the ResourceReader. Models authored on
// Windows use backslashes and get the case of file names wrong (Dabrovic Sponza asks for
// SP_LUK.JPG and ships sp_luk.JPG), so after the exact name we try a case-insensitive match in the
// same folder; glTF URIs may be percent-encoded. When nothing matches, `lookedFor` is the path
// the reference names, for the error.
std::optional<std::string> findTexture(const ResourceReader& resources, std::string ref,
                                       std::string& lookedFor) {
  std::replace(ref.begin(), ref.end(), '\\', '/');
  if (ref.rfind("file://", 0) == 0) ref = ref.substr(7);
  for (const std::string& candidate : {ref, percentDecode(ref)}) {
    const std::string path = normalizeResourcePath(candidate);
    if (resources.exists(path)) return path;
    const std::string folder = resourceFolder(path);
    const std::string want = lower(fs::path(path).filename().string());
    for (const std::string& name : resources.list(folder)) {
      if (lower(name) != want) continue;
      std::string found =
          folder.empty() ? name : (folder.back() == '/' ? folder : folder + "/") + name;
      if (resources.exists(found)) return found;
    }
  }
  lookedFor = normalizeResourcePath(ref);
  return std::nullopt;
}

class AssimpImport {
 public:
  // `file` names the model in messages; `assimpPath` is the name Assimp read it under.
  AssimpImport(const std::string& file, const std::string& assimpPath,
               std::span<const std::byte> bytes, const ResourceReader& resources, const aiScene& ai)
      : path_(file), file_(file), resources_(resources), ai_(ai), format_(formatOf(assimpPath)) {
    scene_.name = path_.stem().string();
    scene_.up = Vec3(0.0f, 1.0f, 0.0f);
    if (format_ == Format::Gltf) gltf_ = readGltfExtras(bytes);
  }

  Scene run() {
    importMaterials();
    std::vector<int> uses(ai_.mNumMeshes, 0);
    importNode(ai_.mRootNode, glm::mat4(1.0f), uses);
    if (scene_.triangleCount() == 0) throw Error(fmt::format("{}: contains no triangles", file_));
    importLights();
    importCameras();
    return std::move(scene_);
  }

 private:
  std::string materialName(unsigned index) const {
    aiString name;
    if (ai_.mMaterials[index]->Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0)
      return name.C_Str();
    return fmt::format("{}#material{}", path_.filename().string(), index);
  }

  // Only materials that some triangle mesh uses are kept (OBJ files get an unused
  // "DefaultMaterial"; glTF files an unused default), in Assimp's order.
  void importMaterials() {
    std::vector<bool> used(ai_.mNumMaterials, false);
    for (unsigned i = 0; i < ai_.mNumMeshes; ++i) {
      const aiMesh* m = ai_.mMeshes[i];
      if ((m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && m->mMaterialIndex < used.size())
        used[m->mMaterialIndex] = true;
    }
    materialMap_.assign(ai_.mNumMaterials, -1);
    for (unsigned i = 0; i < ai_.mNumMaterials; ++i) {
      if (!used[i]) continue;
      materialMap_[i] = int(scene_.materials.size());
      scene_.materials.push_back(importMaterial(i));
    }
  }

  // How much light the file says passes straight through the material (its base colour `base`):
  // an illumination model with transparency (OBJ illum 4, 6, 7, 9) with a transmission filter (Tf)
  // that is not black passes Tf; else a dissolve below 1 (d, or Tr) passes 1 - d; glTF's
  // KHR_materials_transmission passes its factor times the base colour, alpha blending 1 - alpha.
  // Zero: opaque. (Clamped to [0, 1] by the caller.)
  Rgb transmittance(const aiMaterial& am, Rgb base) const {
    float opacity = 1.0f;
    am.Get(AI_MATKEY_OPACITY, opacity);
    if (!std::isfinite(opacity)) opacity = 1.0f;
    if (format_ == Format::Gltf) {
      float transmission = 0.0f;
      am.Get(AI_MATKEY_TRANSMISSION_FACTOR, transmission);
      if (std::isfinite(transmission) && transmission > 0.0f) return transmission * base;
      aiString mode;
      const bool blends = am.Get(AI_MATKEY_GLTF_ALPHAMODE, mode) == AI_SUCCESS && std::string(mode.C_Str()) == "BLEND";
      return blends && opacity < 1.0f ? Rgb(1.0f - opacity) : Rgb(0.0f);
    }
    int illum = 0;
    aiColor3D filter(0.0f, 0.0f, 0.0f);
    if (am.Get(AI_MATKEY_OBJ_ILLUM, illum) == AI_SUCCESS && (illum == 4 || illum == 6 || illum == 7 || illum == 9) &&
        am.Get(AI_MATKEY_COLOR_TRANSPARENT, filter) == AI_SUCCESS && filter.r + filter.g + filter.b > 0.0f)
      return Rgb(filter.r, filter.g, filter.b);
    return opacity < 1.0f ? Rgb(1.0f - opacity) : Rgb(0.0f);
  }

  Material importMaterial(unsigned index) {
    const aiMaterial& am = *ai_.mMaterials[index];
    Material mat;
    mat.name = materialName(index);

    // glTF gives baseColorFactor (Assimp copies it into the diffuse colour as well); OBJ Kd,
    // FBX and COLLADA give the diffuse colour.
    aiColor4D base(0.8f, 0.8f, 0.8f, 1.0f);
    bool haveBase = am.Get(AI_MATKEY_BASE_COLOR, base) == AI_SUCCESS;
    if (!haveBase) am.Get(AI_MATKEY_COLOR_DIFFUSE, base);
    Rgb reflectance(base.r, base.g, base.b);
    Rgb clamped;
    bool outside = false;  // of [0, 1], where the file's value is wrong, not just capped by luxel
    for (int c = 0; c < 3; ++c) {
      clamped[c] =
          std::isfinite(reflectance[c]) ? std::clamp(reflectance[c], 0.0f, kMaxReflectance) : 0.0f;
      outside |= !(reflectance[c] >= 0.0f && reflectance[c] <= 1.0f);
    }
    // Up to 1 is a valid colour (glTF's default base colour is 1, and emitters keep it): capping
    // it at kMaxReflectance is luxel's business, not something the file should be warned about.
    if (outside)
      scene_.warnings.push_back(
          fmt::format("{}: material '{}': reflectance ({}, {}, {}) clamped to [0, {}]", file_,
                      mat.name, reflectance.x, reflectance.y, reflectance.z, kMaxReflectance));
    mat.reflectance = clamped;

    aiColor4D emissive(0.0f, 0.0f, 0.0f, 1.0f);
    am.Get(AI_MATKEY_COLOR_EMISSIVE, emissive);
    Rgb emissiveFactor(emissive.r, emissive.g, emissive.b);
    if (format_ == Format::Fbx && emissiveFactor == Rgb(0.0f)) {
      // FBX files may carry only the legacy "Emissive" (EmissiveColor * EmissiveFactor, as
      // Assimp's own FBX exporter writes it); Assimp maps EmissiveColor alone and passes the
      // rest through as "$raw." properties.
      aiColor3D legacy(0.0f, 0.0f, 0.0f);
      if (am.Get("$raw.Emissive", 0, 0, legacy) == AI_SUCCESS)
        emissiveFactor = Rgb(legacy.r, legacy.g, legacy.b);
    }
    float strength = 1.0f;
    if (am.Get(AI_MATKEY_EMISSIVE_INTENSITY, strength) != AI_SUCCESS) {
      strength = 1.0f;
      if (gltf_) {
        bool ambiguous = false;
        strength = gltfEmissiveStrength(*gltf_, haveMaterialName(am) ? mat.name : std::string(),
                                        emissiveFactor, Rgb(base.r, base.g, base.b), ambiguous);
        if (ambiguous)
          scene_.warnings.push_back(
              fmt::format("{}: material '{}': several glTF materials match with different "
                          "KHR_materials_emissive_strength; used {}",
                          file_, mat.name, strength));
      }
    }
    Rgb emission = emissiveFactor * strength;
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(emission[c]) || emission[c] < 0.0f) {
        scene_.warnings.push_back(fmt::format(
            "{}: material '{}': emission ({}, {}, {}) is negative or not finite; set to 0", file_,
            mat.name, emission.x, emission.y, emission.z));
        emission = Rgb(0.0f);
        break;
      }
    }
    mat.emission = emission;

    int twoSided = 0;
    if (am.Get(AI_MATKEY_TWOSIDED, twoSided) == AI_SUCCESS) mat.twoSided = twoSided != 0;

    importSpecular(am, mat);
    // Glass passes at most what it does not reflect: more would make light.
    const Rgb passes = transmittance(am, Rgb(base.r, base.g, base.b));
    for (int c = 0; c < 3; ++c)
      mat.transmittance[c] = std::isfinite(passes[c]) ? std::clamp(passes[c], 0.0f, 1.0f - mat.reflectance[c]) : 0.0f;
    if (mat.transmittance != glm::clamp(passes, Rgb(0.0f), Rgb(1.0f)))
      scene_.warnings.push_back(fmt::format(
          "{}: material '{}': transmittance ({}, {}, {}) lowered to ({}, {}, {}): with its reflectance it would pass "
          "and reflect more light than arrives",
          file_, mat.name, passes.r, passes.g, passes.b, mat.transmittance.r, mat.transmittance.g, mat.transmittance.b));

    mat.reflectanceTexture =
        materialTexture(am, mat.name, {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE});
    // glTF's emissive factor defaults to black, and black times the texture is black: skip the
    // decode unless the material emits.
    if (mat.isEmissive())
      mat.emissionTexture = materialTexture(am, mat.name, {aiTextureType_EMISSIVE});
    importNormalMap(am, mat);
    return mat;
  }

  // A normal map (glTF normalTexture, OBJ norm, FBX NormalMap: Assimp's NORMALS), else a bump map
  // (OBJ bump and map_Bump, Assimp's HEIGHT) made into one (scene/bump_map.h). Texels are data:
  // read without the sRGB curve. The scale is glTF's normalTexture.scale or OBJ's -bm, which
  // Blender writes as its normal maps' strength.
  void importNormalMap(const aiMaterial& am, Material& mat) {
    if (std::optional<std::string> ref = textureReference(am, {aiTextureType_NORMALS})) {
      mat.normalTexture = readTexture(*ref, mat.name, false, "normal");
      mat.normalScale = multiplier(am, aiTextureType_NORMALS, mat, 1.0f);
      return;
    }
    std::optional<std::string> ref = textureReference(am, {aiTextureType_HEIGHT});
    if (!ref) return;
    const float bm = multiplier(am, aiTextureType_HEIGHT, mat, kDefaultBumpMultiplier);
    mat.normalTexture = readTexture(*ref, mat.name, false, fmt::format("bump {:a}", bm), [&](Texture t) {
      if (!looksLikeNormalMap(t)) return normalMapFromHeight(t, bm);
      scene_.warnings.push_back(fmt::format(
          "{}: material '{}': bump map '{}' is coloured and bluish, a normal map: read as one", file_, mat.name, t.path));
      bumpNormalMaps_.insert(t.path);
      return t;
    });
    // A normal map in the bump slot keeps -bm as its scale; a height map has it built in.
    if (bumpNormalMaps_.count(scene_.textures[size_t(mat.normalTexture)].path)) mat.normalScale = bm;
  }

  // glTF's $tex.scale or OBJ's $tex.bumpmult for the first texture of `type`; `otherwise` when the
  // file gives neither, or gives something not finite (with a warning).
  float multiplier(const aiMaterial& am, aiTextureType type, const Material& mat, float otherwise) {
    float v = otherwise;
    if (am.Get(AI_MATKEY_GLTF_TEXTURE_SCALE(type, 0), v) != AI_SUCCESS &&
        am.Get(AI_MATKEY_OBJ_BUMPMULT(type, 0), v) != AI_SUCCESS)
      return otherwise;
    if (std::isfinite(v)) return v;
    scene_.warnings.push_back(fmt::format("{}: material '{}': normal or bump map scale {} is not finite; using {:g}",
                                          file_, mat.name, v, otherwise));
    return otherwise;
  }

  // The display-only Blinn-Phong highlight (Material::specular and shininess): the specular colour
  // (OBJ Ks, FBX SpecularColor times SpecularFactor, COLLADA <specular>) and exponent (OBJ Ns).
  // None where the material asks for diffuse shading only: OBJ illum 0 and 1 (Assimp keeps the
  // file's illum, 1 when the MTL gives none; its shading model says Gouraud for illum 3 to 10,
  // which all have highlights), or a shading model without one (COLLADA <lambert> and
  // <constant>, FBX lambert). glTF's metallic-roughness materials have no Phong terms: none.
  void importSpecular(const aiMaterial& am, Material& mat) {
    if (format_ == Format::Gltf) return;
    if (int illum = 1; am.Get(AI_MATKEY_OBJ_ILLUM, illum) == AI_SUCCESS) {
      if (illum < 2) return;
    } else if (int model = 0; am.Get(AI_MATKEY_SHADING_MODEL, model) == AI_SUCCESS) {
      switch (model) {
        case aiShadingMode_Flat:
        case aiShadingMode_Gouraud:
        case aiShadingMode_OrenNayar:
        case aiShadingMode_Minnaert:
        case aiShadingMode_NoShading:
          return;
        default:
          break;
      }
    }
    aiColor3D ks(0.0f, 0.0f, 0.0f);
    if (am.Get(AI_MATKEY_COLOR_SPECULAR, ks) != AI_SUCCESS) return;
    float strength = 1.0f, shininess = 0.0f;
    am.Get(AI_MATKEY_SHININESS_STRENGTH, strength);
    am.Get(AI_MATKEY_SHININESS, shininess);

    // NaN or a negative value is a broken file, not a colour to guess at.
    auto bad = [](float v) { return !(v >= 0.0f); };
    if (bad(ks.r) || bad(ks.g) || bad(ks.b))
      throw Error(fmt::format("{}: material '{}': specular colour ({}, {}, {}) is negative or not a number",
                              file_, mat.name, ks.r, ks.g, ks.b));
    if (bad(strength))
      throw Error(fmt::format("{}: material '{}': specular strength {} is negative or not a number", file_,
                              mat.name, strength));
    if (bad(shininess))
      throw Error(fmt::format("{}: material '{}': shininess {} is negative or not a number", file_,
                              mat.name, shininess));

    const Rgb specular = Rgb(ks.r, ks.g, ks.b) * strength;
    Rgb clamped;
    bool above = false;
    for (int c = 0; c < 3; ++c) {
      clamped[c] = std::isnan(specular[c]) ? 0.0f : std::min(specular[c], 1.0f);  // NaN: inf * 0
      above |= specular[c] > 1.0f;
    }
    if (above)
      scene_.warnings.push_back(fmt::format("{}: material '{}': specular colour ({}, {}, {}) clamped to [0, 1]",
                                            file_, mat.name, specular.x, specular.y, specular.z));
    mat.specular = clamped;
    mat.shininess = std::min(shininess, kMaxShininess);
    if (shininess > kMaxShininess)
      scene_.warnings.push_back(fmt::format("{}: material '{}': shininess {} clamped to {:g}", file_,
                                            mat.name, shininess, kMaxShininess));
  }

  static bool haveMaterialName(const aiMaterial& am) {
    aiString name;
    return am.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0;
  }

  // The reference of the first texture of the first type present, if any.
  static std::optional<std::string> textureReference(const aiMaterial& am,
                                                     std::initializer_list<aiTextureType> types) {
    aiString ref;
    for (aiTextureType t : types)
      if (am.GetTextureCount(t) > 0 && am.GetTexture(t, 0, &ref) == AI_SUCCESS && ref.length > 0)
        return std::string(ref.C_Str());
    return std::nullopt;
  }

  // The first texture of the first type present, decoded from sRGB (base colour and emissive
  // textures are sRGB-encoded in glTF, and in practice in every other format).
  int materialTexture(const aiMaterial& am, const std::string& matName,
                      std::initializer_list<aiTextureType> types) {
    std::optional<std::string> ref = textureReference(am, types);
    return ref ? readTexture(*ref, matName, true, "colour") : -1;
  }

  // The texture `refStr` refers to (embedded, or a file the ResourceReader finds), decoded from
  // sRGB when `srgb`, else read as stored (data: normal and bump maps). Each file is decoded once
  // per `use`: a file read both ways is two textures.
  // `finish` turns the decoded image into the texture kept (the identity but for bump maps).
  int readTexture(const std::string& refStr, const std::string& matName, bool srgb, const std::string& use,
                  const std::function<Texture(Texture)>& finish = {}) {
    if (const aiTexture* embedded = ai_.GetEmbeddedTexture(refStr.c_str())) {
      std::string key = use + " embedded:" + refStr;
      if (auto it = textureIndex_.find(key); it != textureIndex_.end()) return it->second;
      std::string name = fmt::format("{}#{}", file_, refStr);
      Texture tex;
      try {
        tex = decodeEmbedded(*embedded, name, srgb);
      } catch (const Error& e) {
        throw Error(fmt::format("{}: material '{}': {}", file_, matName, e.what()));
      }
      return addTexture(key, finish ? finish(std::move(tex)) : std::move(tex));
    }

    std::string lookedFor;
    std::optional<std::string> resource = findTexture(resources_, refStr, lookedFor);
    auto notFound = [&](const std::string& path) {
      return Error(fmt::format("{}: material '{}': texture '{}' not found (looked for '{}')", file_,
                               matName, refStr, resources_.describe(path)));
    };
    if (!resource) throw notFound(lookedFor);
    std::string key = use + " file:" + *resource;
    if (auto it = textureIndex_.find(key); it != textureIndex_.end()) return it->second;
    std::optional<std::vector<std::byte>> bytes;
    try {
      bytes = resources_.read(*resource);
    } catch (const Error& e) {
      // The reader says "'<path>': <why>"; as loadTexture did: "texture '<path>': <why>".
      throw Error(fmt::format("{}: material '{}': texture {}", file_, matName, e.what()));
    }
    if (!bytes) throw notFound(*resource);  // gone between exists() and read()
    Texture tex;
    try {
      tex = decodeTextureBytes(*bytes, srgb, resources_.describe(*resource));
    } catch (const Error& e) {
      throw Error(fmt::format("{}: material '{}': {}", file_, matName, e.what()));
    }
    return addTexture(key, finish ? finish(std::move(tex)) : std::move(tex));
  }

  int addTexture(const std::string& key, Texture tex) {
    int index = int(scene_.textures.size());
    scene_.textures.push_back(std::move(tex));
    textureIndex_[key] = index;
    return index;
  }

  static Texture decodeEmbedded(const aiTexture& t, const std::string& name, bool srgb) {
    if (t.mHeight == 0) {
      // Compressed (PNG, JPEG, ...): mWidth is the size in bytes.
      return decodeTexture(reinterpret_cast<const unsigned char*>(t.pcData), t.mWidth, srgb, name);
    }
    // Raw BGRA8 texels, top row first like every image format.
    checkTextureSize(name, t.mWidth, t.mHeight);
    Texture tex;
    tex.path = name;
    tex.width = int(t.mWidth);
    tex.height = int(t.mHeight);
    tex.texels.resize(size_t(t.mWidth) * size_t(t.mHeight));
    for (unsigned y = 0; y < t.mHeight; ++y) {
      for (unsigned x = 0; x < t.mWidth; ++x) {
        const aiTexel& px = t.pcData[size_t(t.mHeight - 1 - y) * t.mWidth + x];
        Rgb c(px.r / 255.0f, px.g / 255.0f, px.b / 255.0f);
        if (srgb) c = Rgb(srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z));
        tex.texels[size_t(y) * t.mWidth + x] = c;
      }
    }
    return tex;
  }

  // Depth first, parents before children, children in order; with an explicit stack, because a
  // file can nest nodes deeper than the call stack goes.
  void importNode(const aiNode* root, const glm::mat4& rootParent, std::vector<int>& uses) {
    std::vector<std::pair<const aiNode*, glm::mat4>> pending{{root, rootParent}};
    while (!pending.empty()) {
      const auto [node, parent] = pending.back();
      pending.pop_back();
      if (!node) continue;
      const glm::mat4 global = parent * toGlm(node->mTransformation);
      // A node with meshes is an object: its meshes are placed by its global transform.
      const size_t firstMesh = scene_.meshes.size();
      for (unsigned k = 0; k < node->mNumMeshes; ++k) {
        unsigned index = node->mMeshes[k];
        if (index >= ai_.mNumMeshes) continue;
        importMesh(index, global, uses[index]++);
      }
      if (scene_.meshes.size() > firstMesh) {
        const uint32_t object = uint32_t(scene_.objects.size());
        std::string name = node->mName.length > 0 ? std::string(node->mName.C_Str())
                                                  : fmt::format("{}#node{}", path_.filename().string(), object);
        scene_.objects.push_back(Object{.name = std::move(name), .transform = global});
        for (size_t m = firstMesh; m < scene_.meshes.size(); ++m) scene_.meshes[m].object = object;
      }
      for (unsigned c = node->mNumChildren; c-- > 0;) pending.emplace_back(node->mChildren[c], global);
    }
  }

  void importMesh(unsigned index, const glm::mat4& transform, int instance) {
    const aiMesh& am = *ai_.mMeshes[index];
    if (!(am.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return;  // points and lines
    Mesh mesh;
    mesh.name = am.mName.length > 0 ? std::string(am.mName.C_Str())
                                    : fmt::format("{}#{}", path_.filename().string(), index);
    if (instance > 0) mesh.name += fmt::format("#{}", instance);  // the same mesh placed again

    mesh.positions.resize(am.mNumVertices);
    for (unsigned v = 0; v < am.mNumVertices; ++v) mesh.positions[v] = toVec3(am.mVertices[v]);
    if (am.HasTextureCoords(0)) {
      mesh.uvs.resize(am.mNumVertices);
      for (unsigned v = 0; v < am.mNumVertices; ++v)
        mesh.uvs[v] = Vec2(am.mTextureCoords[0][v].x, am.mTextureCoords[0][v].y);
    }
    // The second set (glTF TEXCOORD_1, a second OBJ/FBX channel) is the lightmap layout, taken
    // exactly as the first: as Assimp delivers it.
    if (am.HasTextureCoords(1)) {
      mesh.lightmapUvs.resize(am.mNumVertices);
      for (unsigned v = 0; v < am.mNumVertices; ++v)
        mesh.lightmapUvs[v] = Vec2(am.mTextureCoords[1][v].x, am.mTextureCoords[1][v].y);
    }

    std::vector<std::array<uint32_t, 3>> triangles;
    triangles.reserve(am.mNumFaces);
    for (unsigned f = 0; f < am.mNumFaces; ++f) {
      const aiFace& face = am.mFaces[f];
      if (face.mNumIndices != 3) continue;
      std::array<uint32_t, 3> t{face.mIndices[0], face.mIndices[1], face.mIndices[2]};
      for (uint32_t v : t)
        if (v >= am.mNumVertices)
          throw Error(fmt::format("{}: mesh '{}': face {} references vertex {} of {}", file_,
                                  mesh.name, f, v, am.mNumVertices));
      triangles.push_back(t);
    }
    if (triangles.empty()) return;
    mesh.faces = recoverQuads(mesh.positions, triangles);

    int material = am.mMaterialIndex < materialMap_.size() ? materialMap_[am.mMaterialIndex] : -1;
    if (material < 0)
      throw Error(fmt::format("{}: mesh '{}': material index {} out of range", file_, mesh.name,
                              am.mMaterialIndex));
    mesh.material = uint32_t(material);

    checkFinite(mesh, "");
    transformMesh(mesh, transform);
    checkFinite(mesh, " after its node transform");
    scene_.meshes.push_back(std::move(mesh));
  }

  void checkFinite(const Mesh& mesh, const char* when) const {
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      Vec3 p = mesh.positions[v];
      if (!finite(p))
        throw Error(fmt::format("{}: mesh '{}': vertex {} is not finite ({}, {}, {}){}", file_,
                                mesh.name, v, p.x, p.y, p.z, when));
    }
  }

  glm::mat4 nodeTransform(const aiString& name) const {
    const aiNode* node = name.length > 0 ? ai_.mRootNode->FindNode(name) : nullptr;
    return node ? globalTransform(node) : glm::mat4(1.0f);
  }

  // Assimp stores glTF's color * intensity in mColorDiffuse. We split it as colour = c / max(c),
  // intensity = max(c): for glTF lights whose colour peaks at 1 (the usual case) that gives back
  // the file's colour and intensity (candela for point and spot lights, lux for directional), and
  // in every case Light::power() equals what the file says.
  void importLights() {
    for (unsigned i = 0; i < ai_.mNumLights; ++i) {
      const aiLight& al = *ai_.mLights[i];
      std::string name = al.mName.length > 0
                             ? std::string(al.mName.C_Str())
                             : fmt::format("{}#light{}", path_.filename().string(), i);
      Light light;
      light.name = name;
      switch (al.mType) {
        case aiLightSource_POINT:
          light.type = Light::Type::Point;
          break;
        case aiLightSource_SPOT:
          light.type = Light::Type::Spot;
          break;
        case aiLightSource_DIRECTIONAL:
          light.type = Light::Type::Directional;
          break;
        default:
          scene_.warnings.push_back(fmt::format(
              "{}: light '{}': ambient, area and undefined lights are not supported; skipped",
              file_, name));
          continue;
      }
      Rgb c(al.mColorDiffuse.r, al.mColorDiffuse.g, al.mColorDiffuse.b);
      float peak = std::max({c.x, c.y, c.z});
      if (!finite(c) || c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) {
        scene_.warnings.push_back(
            fmt::format("{}: light '{}': colour ({}, {}, {}) is negative or not finite; skipped",
                        file_, name, c.x, c.y, c.z));
        continue;
      }
      light.color = peak > 0.0f ? c / peak : Rgb(1.0f);
      light.intensity = peak;
      light.position = toVec3(al.mPosition);
      Vec3 dir = toVec3(al.mDirection);
      if (light.type != Light::Type::Point) {
        if (!(glm::length(dir) > 0.0f) || !finite(dir)) dir = Vec3(0.0f, 0.0f, -1.0f);
        light.direction = glm::normalize(dir);
      }
      if (light.type == Light::Type::Spot) {
        // glTF's innerConeAngle/outerConeAngle are angles from the axis; Assimp copies them
        // unchanged, and luxel uses the same convention.
        // KHR_lights_punctual: 0 <= inner < outer <= pi/2. Out of range, the file's cone is not
        // what renders, so say which one is used instead. (inner == outer, a hard edge, is what
        // Blender exports for a spot without blend; luxel renders it as written.)
        const float inner = al.mAngleInnerCone, outer = al.mAngleOuterCone;
        float usedOuter = outer, usedInner = inner;
        if (!std::isfinite(outer) || outer <= 0.0f || outer > 0.5f * kPi) usedOuter = 0.25f * kPi;
        if (!std::isfinite(inner) || inner < 0.0f) usedInner = 0.0f;
        usedInner = std::min(usedInner, usedOuter);
        if (usedOuter != outer || usedInner != inner)
          scene_.warnings.push_back(fmt::format(
              "{}: light '{}': spot cone angles inner {:g} and outer {:g} rad are outside 0 <= inner <= outer <= "
              "pi/2; using inner {:g} and outer {:g} rad",
              file_, name, inner, outer, usedInner, usedOuter));
        light.outerConeAngle = usedOuter;
        light.innerConeAngle = usedInner;
      }
      transformLight(light, nodeTransform(al.mName));
      scene_.lights.push_back(light);
    }
  }

  void importCameras() {
    for (unsigned i = 0; i < ai_.mNumCameras; ++i) {
      const aiCamera& ac = *ai_.mCameras[i];
      Camera cam;
      cam.name = ac.mName.length > 0 ? std::string(ac.mName.C_Str())
                                     : fmt::format("{}#camera{}", path_.filename().string(), i);
      if (ac.mHorizontalFOV <= 0.0f && ac.mOrthographicWidth > 0.0f) {
        scene_.warnings.push_back(fmt::format(
            "{}: camera '{}': orthographic cameras are not supported; skipped", file_, cam.name));
        continue;
      }
      std::optional<float> fovY = verticalFov(ac);
      if (!fovY) {
        scene_.warnings.push_back(
            fmt::format("{}: camera '{}': field of view {} rad is unusable; using {} degrees",
                        file_, cam.name, ac.mHorizontalFOV, cam.fovY));
      } else {
        cam.fovY = *fovY;
      }
      // glTF cameras sit at their node's origin; Assimp 5.2 also copies the node translation
      // into mPosition, which would count it twice.
      Vec3 position = format_ == Format::Gltf ? Vec3(0.0f) : toVec3(ac.mPosition);
      Vec3 look = toVec3(ac.mLookAt);
      if (!(glm::length(look) > 0.0f) || !finite(look)) look = Vec3(0.0f, 0.0f, -1.0f);
      Vec3 up = toVec3(ac.mUp);
      if (!(glm::length(up) > 0.0f) || !finite(up)) up = Vec3(0.0f, 1.0f, 0.0f);
      cam.eye = position;
      cam.target = position + glm::normalize(look);
      cam.up = glm::normalize(up);
      transformCamera(cam, nodeTransform(ac.mName));
      scene_.cameras.push_back(cam);
    }
  }

  // The vertical field of view in degrees. aiCamera documents mHorizontalFOV as the half angle
  // ("the angle between the center line of the screen and the left or right border",
  // assimp/camera.h), but importers disagree: COLLADA and FBX store their full horizontal angle
  // (xfov, FieldOfView) as is, and glTF is read from the file (see gltf_extras.h). With the
  // half-width h = tan(half horizontal angle), the half-height is h / aspect.
  std::optional<float> verticalFov(const aiCamera& ac) const {
    float aspect = ac.mAspect > 0.0f && std::isfinite(ac.mAspect) ? ac.mAspect : 1.0f;
    float fovY = 0.0f;  // radians
    if (format_ == Format::Gltf) {
      std::optional<float> yfov = gltf_ ? gltfCameraYFov(*gltf_, ac.mName.C_Str()) : std::nullopt;
      fovY = yfov ? *yfov : ac.mHorizontalFOV / aspect;  // Assimp 5.2 stores yfov * aspect
    } else {
      float half = format_ == Format::Other ? ac.mHorizontalFOV : 0.5f * ac.mHorizontalFOV;
      if (!(half > 0.0f) || !(half < 0.5f * kPi)) return std::nullopt;
      fovY = 2.0f * std::atan(std::tan(half) / aspect);
    }
    if (!(fovY > 0.0f) || !(fovY < kPi)) return std::nullopt;
    return fovY * 180.0f / kPi;
  }

  fs::path path_;     // `file` as a path, for its stem and file name
  std::string file_;  // what messages call the model
  const ResourceReader& resources_;
  const aiScene& ai_;
  Format format_;
  std::optional<GltfExtras> gltf_;
  Scene scene_;
  std::vector<int> materialMap_;             // Assimp material index -> scene material, -1 unused
  std::map<std::string, int> textureIndex_;  // each image decoded once per use
  std::set<std::string> bumpNormalMaps_;     // images in a bump slot read as normal maps
};

bool hasPolygons(const aiScene& ai) {
  for (unsigned i = 0; i < ai.mNumMeshes; ++i) {
    const aiMesh* m = ai.mMeshes[i];
    for (unsigned f = 0; m && f < m->mNumFaces; ++f)
      if (m->mFaces[f].mNumIndices >= 3) return true;
  }
  return false;
}

// Assimp's messages name its own structures ("aiMesh::mFaces[3] is a LINE") or say nothing a user
// can act on ("No suitable reader found for the file format of file ..."): translate those, and
// keep the ones that describe the file in its format's terms ("OBJ: ...").
std::string assimpError(const std::string& raw, const std::string& assimpPath) {
  const std::string ext = lower(fs::path(assimpPath).extension().string());
  if (raw.find("No suitable reader") != std::string::npos || raw.find("Unable to open file") != std::string::npos)
    return ext.empty() ? "not in a format luxel can import"
                       : fmt::format("not a valid {} file, nor any other format luxel can import", ext);
  // "FBX-Tokenize (line 2 <<  col 6) unexpected colon", "FBX-Parser (TOK_DATA, line 1, col 20)
  // unexpected token, expected TOK_KEY": the reader's stage and token names, then a position.
  if (raw.rfind("FBX-", 0) == 0) {
    std::smatch at;
    static const std::regex kLine(R"(line (\d+)\D+col (\d+))");
    static const std::regex kOffset(R"(offset (0x[0-9a-fA-F]+))");
    if (std::regex_search(raw, at, kLine))
      return fmt::format("not a valid FBX file: its syntax breaks at line {}, column {}", at[1].str(), at[2].str());
    if (std::regex_search(raw, at, kOffset))
      return fmt::format("not a valid FBX file: its structure breaks at byte {}", at[1].str());
    return "not a valid FBX file";
  }
  for (const char* internal : {"aiMesh", "aiScene", "aiNode", "aiMaterial", "aiFace", "aiAnimation", "mNum", "Validation failed"})
    if (raw.find(internal) != std::string::npos)
      return "malformed: its meshes, faces or nodes refer to data that is not there or of the wrong kind";
  return raw;
}

// The name Assimp reads the main file under: `name`, with ".<hint>" appended unless it already
// ends that way, since Assimp picks its importer from the extension (see assimp_io.h).
std::string assimpMainPath(const std::string& name, std::string hint) {
  if (!hint.empty() && hint.front() == '.') hint.erase(0, 1);
  if (hint.empty()) return name;
  if (hint.find_first_of("/\\") != std::string::npos)
    throw Error(fmt::format("{}: format hint '{}' is not a file extension", name, hint));
  // (fmt rather than "." + string: GCC 12 warns falsely on the latter, -Wrestrict.)
  const std::string suffix = fmt::format(".{}", lower(hint));
  const std::string lowerName = lower(name);
  if (lowerName.size() >= suffix.size() &&
      lowerName.compare(lowerName.size() - suffix.size(), suffix.size(), suffix) == 0)
    return name;
  return name + suffix;
}

}  // namespace

namespace {
Scene importMeshOnThisStack(std::span<const std::byte> bytes, std::string_view formatHint,
                            const ResourceReader& resources, std::string_view name);
Scene readWithAssimp(const std::string& file, const std::string& assimpPath, std::span<const std::byte> bytes,
                     std::string_view formatHint, const ResourceReader& resources);
}  // namespace

Scene importMesh(std::span<const std::byte> bytes, std::string_view formatHint,
                 const ResourceReader& resources, std::string_view name) {
  Scene scene;
  // Assimp recurses as deep as the file's nodes nest (and so does freeing them).
  runOnLargeStack([&] { scene = importMeshOnThisStack(bytes, formatHint, resources, name); });
  return scene;
}

namespace {

Scene importMeshOnThisStack(std::span<const std::byte> bytes, std::string_view formatHint,
                            const ResourceReader& resources, std::string_view name) {
  const std::string file(name);
  const std::string assimpPath = assimpMainPath(file, std::string(formatHint));
  checkPlyCounts(bytes, file);
  checkGlbLayout(bytes, file);
  // The format checks, Assimp and the conversion of what it read, in a child process with limits:
  // a crash, a hang or a memory bomb in any of them is an Error naming the file.
  Scene scene = importInChildProcess(file, bytes.size(),
                                     [&] { return readWithAssimp(file, assimpPath, bytes, formatHint, resources); });
  warnAboutStrayMesh(scene, file);  // first: what follows is measured against the extent
  removeCoincidentFaces(scene);
  return scene;
}

Scene readWithAssimp(const std::string& file, const std::string& assimpPath, std::span<const std::byte> bytes,
                     std::string_view formatHint, const ResourceReader& resources) {
  // Checks for what Assimp would silently repair, format by format (see each header).
  const std::string extension = lower(fs::path(assimpPath).extension().string());
  if (formatOf(assimpPath) == Format::Gltf) checkGltfAccessors(bytes, resources, file);
  if (formatOf(assimpPath) == Format::Collada) checkColladaIndices(bytes, file);
  std::vector<std::string> warnings;
  if (extension == ".obj") warnings = checkObjReferences(bytes, resources, file);

  Assimp::Importer importer;
  importer.SetIOHandler(new ResourceIOSystem(assimpPath, bytes, resources));  // owned by importer
  // Read without post-processing first: validation would reject a file without faces as
  // "Mesh contains no faces", and "contains no triangles" says what is wrong.
  const aiScene* ai = importer.ReadFile(assimpPath, 0);
  if (!ai) {
    const std::string hint = lower(std::string(formatHint));
    if (hint == "gltf" || hint == ".gltf" || hint == "glb" || hint == ".glb")
      if (const std::optional<std::string> why = gltfJsonError(bytes)) throw Error(fmt::format("{}: {}", file, *why));
    throw Error(fmt::format("{}: {}", file, assimpError(importer.GetErrorString(), assimpPath)));
  }
  if (!ai->mRootNode || !hasPolygons(*ai))
    throw Error(fmt::format("{}: contains no triangles", file));
  // Points and lines carry no area: drop them rather than get meshes of them. Validation runs
  // first among the steps, so the others only see indices that are in range.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  ai = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                                    aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (!ai) throw Error(fmt::format("{}: {}", file, assimpError(importer.GetErrorString(), assimpPath)));
  if (ai->mNumMeshes == 0) throw Error(fmt::format("{}: contains no triangles", file));
  Scene scene = AssimpImport(file, assimpPath, bytes, resources, *ai).run();
  scene.warnings.insert(scene.warnings.begin(), warnings.begin(), warnings.end());
  return scene;
}

}  // namespace

Scene importMeshFile(const fs::path& path) {
  const std::string file = path.string();
  if (const std::optional<std::string> why = whyNotARegularFile(path)) throw Error(fmt::format("{}: {}", file, *why));
  // Side files and textures are found next to the model, as they always were.
  const FileResourceReader resources(path.parent_path());
  std::optional<std::vector<std::byte>> bytes;
  try {
    bytes = resources.read(path.filename().string());
  } catch (const Error&) {
    throw Error(fmt::format("{}: cannot open file", file));
  }
  if (!bytes) throw Error(fmt::format("{}: no such file", file));
  std::string ext = path.extension().string();
  return importMesh(*bytes, ext, resources, file);
}

}  // namespace luxel
