// Where a loader reading from memory gets the files a model refers to (an OBJ's .mtl, a .gltf's
// .bin buffers, textures): a ResourceReader answers for paths relative to the main file's folder.
// FileResourceReader reads a folder on disk; MemoryResourceReader serves bytes the caller holds,
// so that a fuzzer or an archive can feed the importers without touching the filesystem.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace luxel {

// Paths given to a reader are as the model wrote them after normalisation: '/' separators,
// lexically normal ("a/./b/../c.png" is "a/c.png"), relative to the main file's folder. They may
// start with "../", and may be absolute when the model names an absolute file.
class ResourceReader {
 public:
  virtual ~ResourceReader() = default;

  // The bytes of the resource at `path`, or nullopt when there is none. Throws Error naming the
  // resource when it exists but cannot be read.
  virtual std::optional<std::vector<std::byte>> read(std::string_view path) const = 0;

  // Whether read(path) would find something, without reading it. The default calls read().
  virtual bool exists(std::string_view path) const;

  // The names of the resources directly in `folder` ("" is the main file's folder), so that a
  // texture reference whose letter case is wrong (common in models authored on Windows) can
  // still be found. The default lists nothing, which disables that fallback.
  virtual std::vector<std::string> list(std::string_view folder) const;

  // What messages and Texture::path call the resource at `path`. The default is `path` itself.
  virtual std::string describe(std::string_view path) const;
};

// Reads files under `root`: read("tex/a.png") is root/tex/a.png. Absolute paths are read as they
// are, and "../" leaves the root, as the file-path loaders always allowed: this is not a sandbox.
class FileResourceReader final : public ResourceReader {
 public:
  explicit FileResourceReader(std::filesystem::path root);

  std::optional<std::vector<std::byte>> read(std::string_view path) const override;
  bool exists(std::string_view path) const override;
  std::vector<std::string> list(std::string_view folder) const override;
  // The file's path: root/path, lexically normal.
  std::string describe(std::string_view path) const override;

 private:
  std::filesystem::path file(std::string_view path) const;

  std::filesystem::path root_;
};

// Serves bytes added to it, by path. Paths are normalised on add() and on lookup as described
// above, so add("tex\\a.png") is found as "tex/a.png" and "./tex/a.png". Nothing outside the map
// is ever read.
class MemoryResourceReader final : public ResourceReader {
 public:
  // Adds or replaces the resource at `path`.
  void add(std::string_view path, std::span<const std::byte> bytes);
  void add(std::string_view path, std::string_view bytes);

  std::optional<std::vector<std::byte>> read(std::string_view path) const override;
  bool exists(std::string_view path) const override;
  std::vector<std::string> list(std::string_view folder) const override;

 private:
  std::map<std::string, std::vector<std::byte>, std::less<>> files_;
};

}  // namespace luxel
