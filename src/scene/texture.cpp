// Textures: bilinear lookup, mean, and decoding image files through stb_image.
#include <stb_image.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <span>
#include <string_view>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "luxel/error.h"
#include "luxel/import.h"
#include "io/input_file.h"
#include "scene/texture_decode.h"

namespace luxel {
namespace {

// Maps a coordinate onto [0,1) for repeat addressing; NaN and infinities become 0 so that a bad
// uv can never index outside the image.
float wrapUnit(float t) {
  if (!std::isfinite(t)) return 0.0f;
  float w = t - std::floor(t);
  return w < 1.0f ? w : 0.0f;  // t slightly below an integer can round up to 1
}

// The two texel indices and the weight of the second, for bilinear filtering with texel centres at
// (i + 0.5) / n and repeat wrap.
void bilinearTaps(float t, int n, int& i0, int& i1, float& f) {
  float x = wrapUnit(t) * float(n) - 0.5f;
  float fl = std::floor(x);
  f = x - fl;
  i0 = int(fl);
  if (i0 < 0) i0 += n;
  if (i0 >= n) i0 -= n;
  i1 = i0 + 1 == n ? 0 : i0 + 1;
}

// 256-entry table: decoding every texel through pow() is slow for large JPEGs.
const std::array<float, 256>& srgbTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgbToLinear(float(i) / 255.0f);
    return t;
  }();
  return table;
}

struct StbFree {
  void operator()(void* p) const { stbi_image_free(p); }
};

// stb_image's reasons are its own shorthand ("first not IHDR", "bad huffman code"): say what it
// means for the file instead.
std::string failure(const std::string& path) {
  const std::string_view reason = stbi_failure_reason() ? stbi_failure_reason() : "";
  if (reason == "unknown image type")
    return fmt::format("texture '{}': not an image luxel reads (PNG, JPEG, TGA, BMP, PSD, GIF, HDR, PIC or PNM)",
                       path);
  if (reason == "outofmem") return fmt::format("texture '{}': out of memory while decoding it", path);
  return fmt::format("texture '{}': the image is damaged or truncated and cannot be decoded", path);
}

}  // namespace

float srgbToLinear(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

Rgb Texture::sample(Vec2 uv) const {
  if (width <= 0 || height <= 0 || texels.size() < size_t(width) * size_t(height))
    return Rgb(1.0f);  // no image: neutral, since textures multiply a colour
  int x0, x1, y0, y1;
  float fx, fy;
  bilinearTaps(uv.x, width, x0, x1, fx);
  bilinearTaps(uv.y, height, y0, y1, fy);  // row 0 is v = 0 (bottom)
  auto at = [&](int x, int y) { return texels[size_t(y) * size_t(width) + size_t(x)]; };
  Rgb bottom = at(x0, y0) * (1.0f - fx) + at(x1, y0) * fx;
  Rgb top = at(x0, y1) * (1.0f - fx) + at(x1, y1) * fx;
  return bottom * (1.0f - fy) + top * fy;
}

Rgb Texture::mean() const {
  if (texels.empty()) return Rgb(0.0f);
  // Double accumulation: a 4k texture has 16M texels, beyond float's exact integers.
  double sum[3] = {0.0, 0.0, 0.0};
  for (const Rgb& t : texels) {
    sum[0] += t.x;
    sum[1] += t.y;
    sum[2] += t.z;
  }
  double n = double(texels.size());
  return Rgb(float(sum[0] / n), float(sum[1] / n), float(sum[2] / n));
}

void checkTextureSize(const std::string& path, long long width, long long height) {
  if (width <= 0 || height <= 0 || width * height > kMaxTexturePixels)
    throw Error(fmt::format("texture '{}': {} x {} texels is {:.0f} megapixels, over the limit of {:.0f} (8192 x 8192; "
                            "{:.1f} GiB as linear float); scale it down",
                            path, width, height, double(width) * double(height) / 1e6, double(kMaxTexturePixels) / 1e6,
                            double(width) * double(height) * sizeof(Rgb) / double(1u << 30)));
}

Texture decodeTexture(const unsigned char* data, size_t size, bool srgb, const std::string& path) {
  if (size == 0) throw Error(fmt::format("texture '{}': file is empty", path));
  if (size > size_t(std::numeric_limits<int>::max()))
    throw Error(fmt::format("texture '{}': file is too large ({} bytes)", path, size));
  int len = int(size);
  int w = 0, h = 0, channels = 0;
  // The header's size first: a few hundred kilobytes of PNG can claim 16000 x 16000 (6 GiB decoded).
  if (stbi_info_from_memory(data, len, &w, &h, &channels)) checkTextureSize(path, w, h);
  Texture tex;
  tex.path = path;
  std::vector<Rgb> rows;  // top row first, as stb_image returns it

  if (stbi_is_hdr_from_memory(data, len)) {
    // Radiance .hdr is linear already: stbi_loadf returns it untouched.
    std::unique_ptr<float, StbFree> px(stbi_loadf_from_memory(data, len, &w, &h, &channels, 3));
    if (!px) throw Error(failure(path));
    rows.resize(size_t(w) * size_t(h));
    for (size_t i = 0; i < rows.size(); ++i) {
      rows[i] = Rgb(px.get()[3 * i], px.get()[3 * i + 1], px.get()[3 * i + 2]);
      if (!(std::max({rows[i].r, rows[i].g, rows[i].b}) <= kMaxRadiance))  // also NaN
        throw Error(fmt::format("texture '{}': texel ({}, {}) is {:g}, over the limit of {:g} for light in float", path,
                                i % size_t(w), i / size_t(w), std::max({rows[i].r, rows[i].g, rows[i].b}), kMaxRadiance));
    }
  } else if (stbi_is_16_bit_from_memory(data, len)) {
    // The file's own channels, expanded to RGB here: asked for 3 channels of a 16-bit PNM with
    // fewer, Debian 12's stb_image converts them with its 8-bit routine into a buffer half the
    // size the 16-bit reader then walks (fuzz-texture found the overflow).
    std::unique_ptr<stbi_us, StbFree> px(stbi_load_16_from_memory(data, len, &w, &h, &channels, 0));
    if (!px) throw Error(failure(path));
    if (channels < 1 || channels > 4) throw Error(fmt::format("texture '{}': {} channels", path, channels));
    rows.resize(size_t(w) * size_t(h));
    for (size_t i = 0; i < rows.size(); ++i) {
      const stbi_us* texel = px.get() + size_t(channels) * i;
      for (int c = 0; c < 3; ++c) {
        // Grey (and grey with alpha) to all three; red, green, blue as they are.
        float v = float(texel[channels < 3 ? 0 : c]) / 65535.0f;
        rows[i][c] = srgb ? srgbToLinear(v) : v;
      }
    }
  } else {
    // Not stbi_loadf for 8-bit images: it applies a plain 2.2 gamma, not the sRGB curve.
    std::unique_ptr<stbi_uc, StbFree> px(stbi_load_from_memory(data, len, &w, &h, &channels, 3));
    if (!px) throw Error(failure(path));
    const std::array<float, 256>& table = srgbTable();
    rows.resize(size_t(w) * size_t(h));
    for (size_t i = 0; i < rows.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        stbi_uc v = px.get()[3 * i + size_t(c)];
        rows[i][c] = srgb ? table[v] : float(v) / 255.0f;
      }
    }
  }
  if (w <= 0 || h <= 0) throw Error(fmt::format("texture '{}': image has no pixels", path));

  // stb_image returns the top row first; texture coordinates put v = 0 at the bottom.
  tex.width = w;
  tex.height = h;
  tex.texels.resize(rows.size());
  for (int y = 0; y < h; ++y)
    std::copy_n(rows.begin() + ptrdiff_t(size_t(h - 1 - y) * size_t(w)), w,
                tex.texels.begin() + ptrdiff_t(size_t(y) * size_t(w)));
  return tex;
}

Texture decodeTextureBytes(std::span<const std::byte> bytes, bool srgb, std::string_view name) {
  return decodeTexture(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), srgb,
                       std::string(name));
}

Texture loadTexture(const std::filesystem::path& path, bool srgb) {
  const std::string name = path.string();
  if (const std::optional<std::string> why = whyNotARegularFile(path))
    throw Error(fmt::format("texture '{}': {}", name, *why));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("texture '{}': cannot open file", name));
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(fmt::format("texture '{}': read error", name));
  return decodeTextureBytes(std::as_bytes(std::span<const char>(bytes)), srgb, name);
}

}  // namespace luxel
