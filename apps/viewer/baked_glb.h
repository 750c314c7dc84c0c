// What `luxel bake` put in a glb, read back as an engine reads it (tinygltf): the meshes as written,
// their materials, and the baked light (docs/baking.md): per-vertex radiance or irradiance
// (COLOR_0 times the scene's vertexColorScale) or lightmaps (RGBM PNG pages on TEXCOORD_1, named in
// each material copy's extras), with the directions of LUXEL_lightmap_directional read at the
// normal map's normal, and the SH transfer of LUXEL_lightmap_transfer relit by a light the viewer
// can turn. The viewer's "baked" view draws it, so a bake can be checked in the same window as the
// live solve.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "luxel/scene.h"

namespace luxel::viewer {

struct BakedGlb {
  struct Primitive {
    std::vector<Vec3> positions;  // world space (node transforms applied)
    std::vector<Vec2> uv0, uv1;   // empty when absent
    std::vector<Rgb> colors;      // COLOR_0 times vertexColorScale; empty when absent
    std::vector<Vec3> normals;       // NORMAL in world space; empty when absent
    std::vector<glm::vec4> tangents; // TANGENT in world space (w: the bitangent's sign); empty when absent
    // LUXEL_vertex_directional (docs/baking.md, "Directions per vertex"): the mode ("" for none)
    // and, per vertex, its attributes' values in the mode's order (unused entries zero).
    std::string directionalMode;
    std::vector<std::array<Vec3, 8>> directions;
    std::vector<uint32_t> indices;
    int material = -1;
  };
  struct Material {
    glm::vec4 baseColor{1.0f};
    int baseTexture = -1;  // image index (sRGB)
    Rgb emission{0.0f};    // emissive factor times KHR_materials_emissive_strength
    int lightmap = -1;     // image index (linear RGBM)
    float rgbmRange = 1.0f;
    bool doubleSided = false;
    int normalTexture = -1;  // image index (linear data)
    float normalScale = 1.0f;
    // LUXEL_lightmap_directional (docs/baking.md): the mode ("" for none) and its textures' images.
    std::string directionalMode;
    std::vector<int> directionImages;
    // LUXEL_lightmap_transfer (docs/baking.md, "Transfer lightmaps in the glb"): bands 0 for none.
    int transferBands = 0;
    int transferBand0 = -1;            // image index: T_0 per channel as RGBM
    float transferBand0Range = 1.0f;
    std::vector<int> transferRatios;   // image indices: q_i = T_i / T_0, four numbers a texel
    std::vector<float> ratioScale;     // per coefficient i >= 1: q_i = (2 texel - 1) * ratioScale[i - 1]
  };
  // The distant light a transfer bake was relit with, as stored (every transfer material holds the
  // same): the skies' radiance SH and each sun's direction of travel and irradiance.
  struct TransferSun {
    Vec3 direction{0.0f, -1.0f, 0.0f};
    Rgb irradiance{0.0f};
  };
  struct TransferLight {
    int bands = 0;  // 0: the glb has no transfer
    std::vector<Rgb> sky;  // bands^2 coefficients
    std::vector<TransferSun> suns;
  };
  struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
  };
  std::vector<Primitive> primitives;
  std::vector<Material> materials;
  std::vector<Image> images;
  std::string vertexColors;  // "radiance", "irradiance", or empty (no vertex colours)
  bool hasLightmaps = false;
  TransferLight transfer;

  bool baked() const { return !vertexColors.empty() || hasLightmaps; }
};

// Reads `path` (.glb or .gltf). Throws luxel::Error naming the file when tinygltf cannot read it,
// an accessor is not what glTF allows, or a material's LUXEL_lightmap_transfer is not what its
// schema says (docs/schema/LUXEL_lightmap_transfer.schema.json) or disagrees with another's.
BakedGlb readBakedGlb(const std::filesystem::path& path);

}  // namespace luxel::viewer
