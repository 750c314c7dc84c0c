// Getting scenes in: mesh files through Assimp, luxel scene files (JSON), and built-in scenes.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "luxel/scene.h"

namespace luxel {

// Imports a mesh file through Assimp: OBJ/MTL, glTF 2.0 (.gltf/.glb), FBX, PLY, COLLADA and the
// other formats Assimp reads. Materials: reflectance from OBJ Kd or glTF baseColorFactor times the
// base colour texture; emission from OBJ Ke, or glTF emissiveFactor times
// KHR_materials_emissive_strength times the emissive texture. KHR_lights_punctual lights and
// cameras are imported. Throws Error naming the file when it is missing, malformed, empty, or
// references a texture that cannot be read.
Scene importMeshFile(const std::filesystem::path& path);

// Loads a luxel scene file (JSON, see docs/scene-format.md). Relative paths resolve against the
// file's directory. Throws Error naming the file and the JSON path of the offending value.
Scene loadSceneFile(const std::filesystem::path& path);

// Loads an image file as a linear-RGB texture. 8-bit images are decoded from sRGB when `srgb`.
// Same as decodeTextureBytes(contents of path, srgb, path.string()), after checking the file.
Texture loadTexture(const std::filesystem::path& path, bool srgb);

// Decodes an image held in memory (PNG, JPEG, TGA, BMP, PSD, GIF, HDR, PIC, PNM: what stb_image
// reads; the format is found from the bytes) into a linear-RGB texture, bottom row first.
// 8- and 16-bit images are decoded from sRGB when `srgb`, else divided by 255 or 65535; Radiance
// .hdr is linear already and `srgb` is ignored. `name` becomes Texture::path and appears in
// errors. Throws Error("texture '<name>': <reason>") when the bytes are empty, not an image,
// truncated, or larger than 2 GiB.
Texture decodeTextureBytes(std::span<const std::byte> bytes, bool srgb, std::string_view name);

// The built-in scenes, by name.
std::vector<std::string> builtinSceneNames();
bool isBuiltinScene(std::string_view name);
Scene builtinScene(std::string_view name);  // throws Error listing the names when unknown

// What `luxel render SCENE` accepts: a built-in name, a .json scene file, or a mesh file.
Scene loadScene(std::string_view spec);

}  // namespace luxel
