// What Assimp 5.2 drops or garbles when it imports glTF 2.0, read from the file's JSON directly:
// KHR_materials_emissive_strength (not supported before Assimp 5.3) and camera yfov (stored in
// aiCamera::mHorizontalFOV as yfov * aspect by 5.2, as a full horizontal angle by later versions,
// while aiCamera documents a half angle).
//
// Assimp loads glTF objects lazily in the order the node graph references them, so aiScene
// indices do not follow the file's arrays: materials are matched by name and factors, and cameras
// by the name of the node that holds them (which Assimp gives the aiCamera).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "luxel/scene.h"

namespace luxel {

struct GltfExtras {
  struct MaterialInfo {
    std::string name;
    Rgb emissiveFactor{0.0f};
    Rgb baseColorFactor{1.0f};
    float emissiveStrength = 1.0f;
  };
  struct CameraNode {
    std::string nodeName;  // as Assimp names the node: "name", or "nodes_<i>" without one
    float yfov = 0.0f;     // radians, full vertical angle
  };
  std::vector<MaterialInfo> materials;
  std::vector<CameraNode> cameraNodes;  // perspective cameras only
};

// Reads the JSON of a .gltf file or the JSON chunk of a .glb file, from the same bytes Assimp
// imported (so that it works for models read from memory). Returns nullopt when they are not
// glTF 2.0 JSON; the caller has already imported them through Assimp, so that only means there
// is nothing extra to read.
std::optional<GltfExtras> readGltfExtras(std::span<const std::byte> bytes);

// The JSON text of a .gltf file, or the JSON and binary chunks of a .glb file (`bin` empty when it
// has none); nullopt when a GLB's JSON chunk is not where its header says.
struct GltfParts {
  std::string_view json;
  std::span<const std::byte> bin;
};
std::optional<GltfParts> gltfParts(std::span<const std::byte> bytes);

// When `bytes` are a GLB file (they start "glTF"), throws Error naming `file` unless its header and
// chunks fit what it holds: version 2, the declared length at most the bytes there are, a JSON
// chunk first, and every chunk inside the declared length. Assimp 5.2 allocates what a chunk
// claims before checking it (1.7 GB for a 23 KB file, found by fuzz-mesh-glb).
void checkGlbLayout(std::span<const std::byte> bytes, const std::string& file);

// Why the JSON of a .gltf file, or of a .glb's JSON chunk, does not parse ("invalid JSON at byte
// 1234: ..."); nullopt when it parses. For the message when Assimp rejects a glTF file: its own is
// "No suitable reader found", which does not say where the file breaks.
std::optional<std::string> gltfJsonError(std::span<const std::byte> bytes);

// The emissive strength of the glTF material that Assimp turned into a material with this name and
// these factors; 1 when none matches. `ambiguous` is set when several match with different
// strengths (the first is returned).
float gltfEmissiveStrength(const GltfExtras& extras, const std::string& name, Rgb emissiveFactor,
                           Rgb baseColorFactor, bool& ambiguous);

// The yfov (radians) of the camera held by the node with this name; nullopt when no node or more
// than one node with different cameras matches.
std::optional<float> gltfCameraYFov(const GltfExtras& extras, const std::string& nodeName);

}  // namespace luxel
