// Assimp's file access pointed at a ResourceReader, so that importMesh reads a model from bytes.
//
// Why a custom IOSystem and a virtual main file rather than Importer::ReadFileFromMemory: Assimp
// picks the importer from the main file's name (its extension) and finds side files by joining
// the main file's folder with the names the model gives (an OBJ's mtllib, a .gltf's buffer
// URIs). ReadFileFromMemory calls the main file "$$$___magic___$$$.<hint>", which would then
// appear in Assimp's messages, and it still opens side files through the installed IOSystem. We
// give Assimp the caller's name for the main file instead (with ".<hint>" appended when it does
// not end that way) and serve every path through one IOSystem: the main file from the caller's
// bytes, everything else from the ResourceReader, relative to the main file's folder. Reading a
// file through importMeshFile is then the same code path with the same names in every message.
#pragma once

#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>

#include <cstddef>
#include <span>
#include <string>
#include <string_view>

#include "luxel/resources.h"

namespace luxel {

class ResourceIOSystem final : public Assimp::IOSystem {
 public:
  // `mainPath` is the name Assimp is asked to read; `mainBytes` and `resources` must outlive
  // the importer that owns this object.
  ResourceIOSystem(std::string mainPath, std::span<const std::byte> mainBytes,
                   const ResourceReader& resources);

  using Assimp::IOSystem::Exists;
  using Assimp::IOSystem::Open;

  bool Exists(const char* file) const override;
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override;
  void Close(Assimp::IOStream* stream) override;

  // Assimp's defaults for these change the process's directory or write to the disk; a reader
  // is read-only.
  bool CreateDirectory(const std::string&) override { return false; }
  bool ChangeDirectory(const std::string&) override { return false; }
  bool DeleteFile(const std::string&) override { return false; }

  // The ResourceReader path for a path Assimp asks for: the main file's folder (which Assimp
  // prefixes to side files) is taken off, and the rest normalised (resource_path.h).
  std::string resourcePath(std::string_view assimpPath) const;

 private:
  bool isMain(const std::string& resource) const { return resource == mainResource_; }

  std::string mainPrefix_;    // the main path up to and including its last '/', or ""
  std::string mainResource_;  // the main file as a resource path (its file name)
  std::span<const std::byte> mainBytes_;
  const ResourceReader& resources_;
};

}  // namespace luxel
