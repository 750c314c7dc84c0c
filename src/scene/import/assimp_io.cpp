// Assimp IOSystem and IOStream over a ResourceReader (see assimp_io.h for why).
#include "scene/import/assimp_io.h"

#include <algorithm>
#include <cstring>
#include <optional>
#include <utility>
#include <vector>

#include "luxel/error.h"
#include "scene/import/resource_path.h"

namespace luxel {
namespace {

// A read-only stream over bytes, either borrowed (the main file) or owned (a side file). Seek
// follows Assimp's MemoryIOStream: aiOrigin_END counts back from the end.
class ByteStream final : public Assimp::IOStream {
 public:
  explicit ByteStream(std::span<const std::byte> borrowed) : bytes_(borrowed) {}
  explicit ByteStream(std::vector<std::byte> owned) : owned_(std::move(owned)), bytes_(owned_) {}

  size_t Read(void* buffer, size_t size, size_t count) override {
    if (size == 0 || count == 0) return 0;
    // Whole elements only, as fread returns them; no multiplication that could overflow.
    const size_t n = std::min(count, (bytes_.size() - pos_) / size);
    if (n > 0) std::memcpy(buffer, bytes_.data() + pos_, n * size);
    pos_ += n * size;
    return n;
  }

  size_t Write(const void*, size_t, size_t) override { return 0; }

  aiReturn Seek(size_t offset, aiOrigin origin) override {
    size_t base = 0;
    switch (origin) {
      case aiOrigin_SET:
        base = 0;
        break;
      case aiOrigin_CUR:
        base = pos_;
        break;
      case aiOrigin_END:
        if (offset > bytes_.size()) return aiReturn_FAILURE;
        pos_ = bytes_.size() - offset;
        return aiReturn_SUCCESS;
      default:
        return aiReturn_FAILURE;
    }
    if (offset > bytes_.size() - base) return aiReturn_FAILURE;
    pos_ = base + offset;
    return aiReturn_SUCCESS;
  }

  size_t Tell() const override { return pos_; }
  size_t FileSize() const override { return bytes_.size(); }
  void Flush() override {}

 private:
  std::vector<std::byte> owned_;  // declared before bytes_, which may view it
  std::span<const std::byte> bytes_;
  size_t pos_ = 0;
};

}  // namespace

ResourceIOSystem::ResourceIOSystem(std::string mainPath, std::span<const std::byte> mainBytes,
                                   const ResourceReader& resources)
    : mainBytes_(mainBytes), resources_(resources) {
  std::replace(mainPath.begin(), mainPath.end(), '\\', '/');
  size_t slash = mainPath.rfind('/');
  if (slash != std::string::npos) mainPrefix_ = mainPath.substr(0, slash + 1);
  mainResource_ = resourcePath(mainPath);
}

std::string ResourceIOSystem::resourcePath(std::string_view assimpPath) const {
  std::string p(assimpPath);
  std::replace(p.begin(), p.end(), '\\', '/');
  if (!mainPrefix_.empty() && p.size() > mainPrefix_.size() && p.rfind(mainPrefix_, 0) == 0)
    p.erase(0, mainPrefix_.size());
  return normalizeResourcePath(p);
}

bool ResourceIOSystem::Exists(const char* file) const {
  if (!file) return false;
  const std::string resource = resourcePath(file);
  if (isMain(resource)) return true;
  try {
    return resources_.exists(resource);
  } catch (const Error&) {
    return false;  // Assimp expects an answer, not an exception; Open fails the same way
  }
}

Assimp::IOStream* ResourceIOSystem::Open(const char* file, const char* mode) {
  if (!file || !mode) return nullptr;
  if (std::strpbrk(mode, "wa+")) return nullptr;  // read-only
  const std::string resource = resourcePath(file);
  if (isMain(resource)) return new ByteStream(mainBytes_);
  std::optional<std::vector<std::byte>> bytes;
  try {
    bytes = resources_.read(resource);
  } catch (const Error&) {
    // Assimp reports a file it cannot open in its own words ("could not open referenced file");
    // an exception thrown through its parsers could leave them half-way.
    return nullptr;
  }
  if (!bytes) return nullptr;
  return new ByteStream(std::move(*bytes));
}

void ResourceIOSystem::Close(Assimp::IOStream* stream) { delete stream; }

}  // namespace luxel
