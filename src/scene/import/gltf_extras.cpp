// Reading the glTF 2.0 JSON that Assimp 5.2 does not pass on (see gltf_extras.h). Specification:
// https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html (GLB layout, section 4.4) and
// KHR_materials_emissive_strength.
#include "scene/import/gltf_extras.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "luxel/error.h"

namespace luxel {
namespace {

using nlohmann::json;

constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kGlbJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kGlbBinChunk = 0x004E4942;   // "BIN\0"
constexpr float kFactorTolerance = 1e-5f;

uint32_t readU32(std::span<const std::byte> b, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);  // GLB is little-endian, as are the machines we build for
  return v;
}

Rgb readColor(const json& j, const char* key, Rgb fallback) {
  auto it = j.find(key);
  if (it == j.end() || !it->is_array() || it->size() < 3) return fallback;
  Rgb c = fallback;
  for (int i = 0; i < 3; ++i)
    if ((*it)[size_t(i)].is_number()) c[i] = (*it)[size_t(i)].get<float>();
  return c;
}

bool near(Rgb a, Rgb b) {
  for (int i = 0; i < 3; ++i)
    if (std::fabs(a[i] - b[i]) > kFactorTolerance * std::max(1.0f, std::fabs(a[i]))) return false;
  return true;
}

}  // namespace

void checkGlbLayout(std::span<const std::byte> bytes, const std::string& file) {
  if (bytes.size() < 4 || readU32(bytes, 0) != kGlbMagic) return;
  if (bytes.size() < 20) throw Error(fmt::format("{}: a GLB of {} bytes is shorter than its 20-byte header", file, bytes.size()));
  if (readU32(bytes, 4) != 2) throw Error(fmt::format("{}: GLB version {} (luxel reads glTF 2.0)", file, readU32(bytes, 4)));
  const uint64_t length = readU32(bytes, 8);
  if (length > bytes.size() || length < 20)
    throw Error(fmt::format("{}: the GLB header declares {} bytes, but the file holds {}", file, length, bytes.size()));
  if (readU32(bytes, 16) != kGlbJsonChunk) throw Error(fmt::format("{}: the GLB's first chunk is not JSON", file));
  for (uint64_t at = 12; at + 8 <= length;) {
    const uint64_t chunk = readU32(bytes, size_t(at));
    if (at + 8 + chunk > length)
      throw Error(fmt::format("{}: a GLB chunk at byte {} claims {} bytes, past the file's {}", file, at, chunk, length));
    at += 8 + chunk;
  }
}

std::optional<std::string> gltfJsonError(std::span<const std::byte> bytes) {
  const char* text = reinterpret_cast<const char*>(bytes.data());
  const char* begin = text;
  const char* end = text + bytes.size();
  size_t offset = 0;
  if (bytes.size() >= 20 && readU32(bytes, 0) == kGlbMagic) {
    const uint32_t chunkLength = readU32(bytes, 12);
    if (readU32(bytes, 16) != kGlbJsonChunk) return "the GLB's first chunk is not JSON";
    if (size_t(chunkLength) > bytes.size() - 20)
      return fmt::format("the GLB's JSON chunk claims {} bytes, but {} follow", chunkLength, bytes.size() - 20);
    offset = 20, begin = text + 20, end = begin + chunkLength;
  }
  try {
    const json parsed = json::parse(begin, end);
    (void)parsed;
  } catch (const json::parse_error& e) {
    std::string what = e.what();
    if (const size_t close = what.find("] "); close != std::string::npos) what = what.substr(close + 2);
    return fmt::format("invalid JSON at byte {}: {}", e.byte + offset, what);
  } catch (const json::exception& e) {
    return fmt::format("invalid JSON: {}", e.what());
  }
  return std::nullopt;
}

std::optional<GltfParts> gltfParts(std::span<const std::byte> bytes) {
  // nlohmann::json parses chars; the bytes are viewed, not copied.
  const char* text = reinterpret_cast<const char*>(bytes.data());
  if (bytes.size() < 20 || readU32(bytes, 0) != kGlbMagic) return GltfParts{std::string_view(text, bytes.size()), {}};
  // Header (magic, version, length), then the JSON chunk (length, type, data), then maybe BIN.
  const uint32_t jsonLength = readU32(bytes, 12);
  if (readU32(bytes, 16) != kGlbJsonChunk || size_t(jsonLength) > bytes.size() - 20) return std::nullopt;
  GltfParts parts{std::string_view(text + 20, jsonLength), {}};
  const size_t binAt = 20 + size_t(jsonLength);
  if (bytes.size() >= binAt + 8 && readU32(bytes, binAt + 4) == kGlbBinChunk) {
    const size_t binLength = std::min<size_t>(readU32(bytes, binAt), bytes.size() - binAt - 8);
    parts.bin = bytes.subspan(binAt + 8, binLength);
  }
  return parts;
}

std::optional<GltfExtras> readGltfExtras(std::span<const std::byte> bytes) {
  if (bytes.empty()) return std::nullopt;
  const std::optional<GltfParts> parts = gltfParts(bytes);
  if (!parts) return std::nullopt;
  const json doc = json::parse(parts->json.begin(), parts->json.end(), nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return std::nullopt;
  auto asset = doc.find("asset");
  if (asset == doc.end() || !asset->is_object() || !asset->contains("version") ||
      !(*asset)["version"].is_string() || (*asset)["version"].get<std::string>().rfind("2", 0) != 0)
    return std::nullopt;

  GltfExtras extras;
  if (auto mats = doc.find("materials"); mats != doc.end() && mats->is_array()) {
    for (const json& m : *mats) {
      if (!m.is_object()) continue;
      GltfExtras::MaterialInfo info;
      if (m.contains("name") && m["name"].is_string()) info.name = m["name"].get<std::string>();
      info.emissiveFactor = readColor(m, "emissiveFactor", Rgb(0.0f));
      if (auto pbr = m.find("pbrMetallicRoughness"); pbr != m.end() && pbr->is_object())
        info.baseColorFactor = readColor(*pbr, "baseColorFactor", Rgb(1.0f));
      const json* strength = nullptr;
      if (auto ext = m.find("extensions"); ext != m.end() && ext->is_object()) {
        if (auto es = ext->find("KHR_materials_emissive_strength");
            es != ext->end() && es->is_object()) {
          if (auto s = es->find("emissiveStrength"); s != es->end() && s->is_number())
            strength = &*s;
        }
      }
      if (strength) info.emissiveStrength = strength->get<float>();
      extras.materials.push_back(std::move(info));
    }
  }

  auto cameras = doc.find("cameras");
  auto nodes = doc.find("nodes");
  if (cameras != doc.end() && cameras->is_array() && nodes != doc.end() && nodes->is_array()) {
    for (size_t i = 0; i < nodes->size(); ++i) {
      const json& n = (*nodes)[i];
      if (!n.is_object() || !n.contains("camera") || !n["camera"].is_number_unsigned()) continue;
      size_t c = n["camera"].get<size_t>();
      if (c >= cameras->size() || !(*cameras)[c].is_object()) continue;
      const json& cam = (*cameras)[c];
      auto persp = cam.find("perspective");
      if (persp == cam.end() || !persp->is_object() || !persp->contains("yfov") ||
          !(*persp)["yfov"].is_number())
        continue;
      float yfov = (*persp)["yfov"].get<float>();
      if (n.contains("name") && n["name"].is_string()) {
        extras.cameraNodes.push_back({n["name"].get<std::string>(), yfov});
      } else {
        // Assimp names unnamed nodes after their index: "nodes_3" in 5.2, "nodes[3]" later.
        extras.cameraNodes.push_back({"nodes_" + std::to_string(i), yfov});
        extras.cameraNodes.push_back({"nodes[" + std::to_string(i) + "]", yfov});
      }
    }
  }
  return extras;
}

float gltfEmissiveStrength(const GltfExtras& extras, const std::string& name, Rgb emissiveFactor,
                           Rgb baseColorFactor, bool& ambiguous) {
  ambiguous = false;
  std::optional<float> found;
  for (const GltfExtras::MaterialInfo& m : extras.materials) {
    if (m.name != name || !near(m.emissiveFactor, emissiveFactor) ||
        !near(m.baseColorFactor, baseColorFactor))
      continue;
    if (!found) {
      found = m.emissiveStrength;
    } else if (*found != m.emissiveStrength) {
      ambiguous = true;
    }
  }
  return found.value_or(1.0f);
}

std::optional<float> gltfCameraYFov(const GltfExtras& extras, const std::string& nodeName) {
  std::optional<float> found;
  for (const GltfExtras::CameraNode& c : extras.cameraNodes) {
    if (c.nodeName != nodeName) continue;
    if (found && *found != c.yfov) return std::nullopt;
    found = c.yfov;
  }
  return found;
}

}  // namespace luxel
