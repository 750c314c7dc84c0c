// Getting scenes in: mesh files through Assimp, luxel scene files (JSON), and built-in scenes.
//
// Each loader comes twice: from memory (importMesh, loadSceneJson, decodeTextureBytes), which is
// what a fuzzer or an archive reader calls, and from a file path (importMeshFile, loadSceneFile,
// loadTexture), which reads the file and calls the memory one. Both throw the same Error
// messages; the memory ones name what the caller passes as `name` where the others name the file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "luxel/resources.h"
#include "luxel/scene.h"

namespace luxel {

// Imports a mesh file through Assimp: OBJ/MTL, glTF 2.0 (.gltf/.glb), FBX, PLY, COLLADA and the
// other formats Assimp reads. Materials: reflectance from OBJ Kd or glTF baseColorFactor times the
// base colour texture; emission from OBJ Ke, or glTF emissiveFactor times
// KHR_materials_emissive_strength times the emissive texture. KHR_lights_punctual lights and
// cameras are imported. Lengths and light units are the file's, unconverted. Throws Error naming
// the file when it is missing, malformed, empty, or references a texture that cannot be read.
// Side files (an OBJ's .mtl, a .gltf's buffers, textures) are read relative to the file's folder.
// Same as importMesh(bytes of path, its extension, FileResourceReader(its folder), path.string()).
Scene importMeshFile(const std::filesystem::path& path);

// Imports a mesh from the bytes of its main file, as importMeshFile does.
//  - `formatHint` is the file extension that says which Assimp importer reads `bytes` ("obj",
//    "gltf", "glb", "ply", "fbx", "dae", ...; case does not matter, a leading '.' is ignored).
//    Empty, or one Assimp does not know, leaves it to Assimp's detection from the content.
//  - `resources` serves the files the model refers to (an OBJ's mtllib, a .gltf's buffer and
//    image URIs, textures), by path relative to the main file's folder (luxel/resources.h).
//    A missing .mtl is not an error (Assimp imports the OBJ without its materials, as from a
//    file); a missing glTF buffer or texture is.
//  - `name` stands for the main file: it starts every error and warning message, gives the
//    scene its name (the stem: "models/box.obj" -> "box") and unnamed meshes theirs, and is the
//    name Assimp sees (with "." + formatHint appended when it does not already end that way).
//    Its folder part, if any, only names things: `resources` decides where side files come from.
// `bytes` and `resources` are only used during the call. Throws Error starting "<name>: " when
// the bytes are empty, malformed or hold no triangles, or a side file is missing or unreadable;
// never reads the filesystem except through `resources`.
Scene importMesh(std::span<const std::byte> bytes, std::string_view formatHint,
                 const ResourceReader& resources, std::string_view name);

// Loads a luxel scene file (JSON, see docs/scene-format.md). Relative paths resolve against the
// file's directory. Throws Error naming the file and the JSON path of the offending value.
// Same as loadSceneJson(contents of path, path.parent_path(), path.string()).
Scene loadSceneFile(const std::filesystem::path& path);

// Loads a luxel scene from JSON text (UTF-8; comments allowed, as in files). Relative paths in it
// (mesh files, textures) resolve against `baseFolder`, on the filesystem; absolute ones are used
// as they are. `name` starts every error message ("<name>: /meshes/0/file: ...") and its stem is
// the scene's name unless the JSON sets "name". Throws Error on invalid JSON (naming the byte),
// on a value of the wrong type or range (naming its JSON path), and when a referenced file cannot
// be loaded (with that file's own message).
Scene loadSceneJson(std::string_view text, const std::filesystem::path& baseFolder,
                    std::string_view name);

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
