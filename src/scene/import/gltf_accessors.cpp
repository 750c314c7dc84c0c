#include "scene/import/gltf_accessors.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <cstring>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "luxel/error.h"
#include "scene/import/gltf_extras.h"
#include "scene/import/resource_path.h"

namespace luxel {
namespace {

using nlohmann::json;

constexpr int kFloat = 5126;

size_t componentBytes(int type) {
  switch (type) {
    case 5120: case 5121: return 1;  // (UNSIGNED_)BYTE
    case 5122: case 5123: return 2;  // (UNSIGNED_)SHORT
    case 5125: case 5126: return 4;  // UNSIGNED_INT, FLOAT
    default: return 0;
  }
}

size_t componentCount(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

// An unsigned integer member, or nullopt when absent or of another type.
std::optional<uint64_t> unsignedAt(const json& j, const char* key) {
  auto it = j.find(key);
  if (it == j.end() || !it->is_number_unsigned()) return std::nullopt;
  return it->get<uint64_t>();
}

const json* element(const json& doc, const char* array, std::optional<uint64_t> index) {
  auto it = doc.find(array);
  if (!index || it == doc.end() || !it->is_array() || *index >= it->size()) return nullptr;
  const json& e = (*it)[*index];
  return e.is_object() ? &e : nullptr;
}

class AccessorCheck {
 public:
  AccessorCheck(const json& doc, std::span<const std::byte> bin, const ResourceReader& resources,
                const std::string& file)
      : doc_(doc), bin_(bin), resources_(resources), file_(file) {}

  void run() {
    checkStrides();
    bool quantized = false;
    if (auto req = doc_.find("extensionsRequired"); req != doc_.end() && req->is_array())
      for (const json& e : *req) quantized |= e.is_string() && e.get<std::string>() == "KHR_mesh_quantization";
    auto meshes = doc_.find("meshes");
    if (meshes == doc_.end() || !meshes->is_array()) return;
    for (size_t m = 0; m < meshes->size(); ++m) {
      const json& mesh = (*meshes)[m];
      if (!mesh.is_object()) continue;
      std::string name = fmt::format("mesh {}", m);
      if (auto n = mesh.find("name"); n != mesh.end() && n->is_string())
        name = fmt::format("mesh '{}'", n->get<std::string>());
      auto prims = mesh.find("primitives");
      if (prims == mesh.end() || !prims->is_array()) continue;
      for (size_t p = 0; p < prims->size(); ++p) {
        const json& prim = (*prims)[p];
        if (!prim.is_object()) continue;
        const std::string where = fmt::format("{}: {}, primitive {}", file_, name, p);
        auto attrs = prim.find("attributes");
        if (attrs == prim.end() || !attrs->is_object()) continue;
        const std::optional<uint64_t> posIndex = unsignedAt(*attrs, "POSITION");
        const json* pos = element(doc_, "accessors", posIndex);
        if (!pos) continue;
        const int type = int(unsignedAt(*pos, "componentType").value_or(kFloat));
        if (type != kFloat && !quantized)
          throw Error(fmt::format("{}: POSITION accessor {} has componentType {}, but positions must be FLOAT "
                                  "(5126) unless the file requires KHR_mesh_quantization",
                                  where, *posIndex, type));
        const std::optional<uint64_t> indexIndex = unsignedAt(prim, "indices");
        if (const json* indices = element(doc_, "accessors", indexIndex))
          checkIndices(*indices, *indexIndex, unsignedAt(*pos, "count").value_or(0), where);
      }
    }
  }

 private:
  // byteStride: 4..252 and a multiple of 4 (3.6.2.4), and at least one element of each accessor
  // reading through the view, or elements overlap.
  void checkStrides() const {
    auto views = doc_.find("bufferViews");
    if (views == doc_.end() || !views->is_array()) return;
    for (size_t v = 0; v < views->size(); ++v) {
      const json& view = (*views)[v];
      if (!view.is_object() || !view.contains("byteStride")) continue;
      const json& stride = view["byteStride"];
      if (!stride.is_number_unsigned() || stride.get<uint64_t>() < 4 || stride.get<uint64_t>() > 252 ||
          stride.get<uint64_t>() % 4 != 0)
        throw Error(fmt::format("{}: bufferView {} has byteStride {}; glTF requires a multiple of 4 from 4 to 252",
                                file_, v, stride.dump()));
    }
    auto accessors = doc_.find("accessors");
    if (accessors == doc_.end() || !accessors->is_array()) return;
    for (size_t a = 0; a < accessors->size(); ++a) {
      const json& acc = (*accessors)[a];
      if (!acc.is_object()) continue;
      const json* view = element(doc_, "bufferViews", unsignedAt(acc, "bufferView"));
      if (!view || !view->contains("byteStride")) continue;
      const auto typeIt = acc.find("type");
      const size_t size = componentBytes(int(unsignedAt(acc, "componentType").value_or(0))) *
                          (typeIt != acc.end() && typeIt->is_string() ? componentCount(typeIt->get<std::string>()) : 0);
      const uint64_t stride = (*view)["byteStride"].get<uint64_t>();
      if (stride < size)
        throw Error(fmt::format("{}: accessor {} has {}-byte elements, but its bufferView {} has byteStride {}",
                                file_, a, size, *unsignedAt(acc, "bufferView"), stride));
    }
  }

  void checkIndices(const json& acc, uint64_t accIndex, uint64_t vertexCount, const std::string& where) {
    const int type = int(unsignedAt(acc, "componentType").value_or(0));
    if (type != 5121 && type != 5123 && type != 5125) return;  // not an index type: Assimp refuses it
    const size_t size = componentBytes(type);
    const uint64_t count = unsignedAt(acc, "count").value_or(0);
    const std::optional<uint64_t> viewIndex = unsignedAt(acc, "bufferView");
    const json* view = element(doc_, "bufferViews", viewIndex);
    if (!view) return;
    const std::vector<unsigned char>* buffer = bufferData(unsignedAt(*view, "buffer"));
    if (!buffer) return;
    const uint64_t start = unsignedAt(*view, "byteOffset").value_or(0) + unsignedAt(acc, "byteOffset").value_or(0);
    // Out of the buffer is Assimp's to report ("buffer too short").
    if (count == 0 || start > buffer->size() || count > (buffer->size() - start) / size) return;
    for (uint64_t i = 0; i < count; ++i) {
      uint32_t index = 0;
      std::memcpy(&index, buffer->data() + start + i * size, size);  // little-endian
      if (index >= vertexCount)
        throw Error(fmt::format("{}: index {} of accessor {} is {}, but POSITION has only {} vertices",
                                where, i, accIndex, index, vertexCount));
    }
  }

  // The bytes of buffer `index`: a data: URI, the GLB's binary chunk, or a file from `resources`.
  const std::vector<unsigned char>* bufferData(std::optional<uint64_t> index) {
    const json* buffer = element(doc_, "buffers", index);
    if (!buffer) return nullptr;
    if (auto cached = buffers_.find(*index); cached != buffers_.end())
      return cached->second ? &*cached->second : nullptr;
    std::optional<std::vector<unsigned char>>& data = buffers_[*index];
    auto uri = buffer->find("uri");
    if (uri == buffer->end() || !uri->is_string()) {
      if (*index == 0 && !bin_.empty()) {
        const auto* b = reinterpret_cast<const unsigned char*>(bin_.data());
        data.emplace(b, b + bin_.size());
      }
    } else if (tinygltf::IsDataURI(uri->get<std::string>())) {
      std::vector<unsigned char> decoded;
      std::string mime;
      if (tinygltf::DecodeDataURI(&decoded, mime, uri->get<std::string>(), 0, false)) data = std::move(decoded);
    } else if (std::optional<std::vector<std::byte>> file =
                   resources_.read(normalizeResourcePath(uri->get<std::string>()))) {
      const auto* b = reinterpret_cast<const unsigned char*>(file->data());
      data.emplace(b, b + file->size());
    }
    return data ? &*data : nullptr;
  }

  const json& doc_;
  std::span<const std::byte> bin_;
  const ResourceReader& resources_;
  const std::string& file_;
  std::map<uint64_t, std::optional<std::vector<unsigned char>>> buffers_;
};

}  // namespace

void checkGltfAccessors(std::span<const std::byte> bytes, const ResourceReader& resources,
                        const std::string& file) {
  const std::optional<GltfParts> parts = gltfParts(bytes);
  if (!parts) return;
  const json doc = json::parse(parts->json.begin(), parts->json.end(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return;
  AccessorCheck(doc, parts->bin, resources, file).run();
}

}  // namespace luxel
