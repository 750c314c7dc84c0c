// Transfer lightmaps in the glb: see addTransferLightmaps in luxel/transfer_lightmap.h.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <stb_image_write.h>

#include "luxel/error.h"
#include "luxel/transfer_lightmap.h"

namespace luxel {
namespace {

void appendBytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<uint8_t>*>(context);
  const auto* p = static_cast<const uint8_t*>(data);
  out->insert(out->end(), p, p + size);
}

float ratio(const TransferBake& t, size_t page, size_t i, int coefficient, int channel) {
  const float t0 = t.planes[0][page][i][channel];
  return t0 > 0.0f ? t.planes[size_t(coefficient)][page][i][channel] / t0 : 0.0f;
}

// Per coefficient i >= 1: the largest |T_i / T_0| on the page (1e-6 at least), its 8 bits' range.
std::vector<float> ratioScales(const TransferBake& t, size_t page) {
  const int count = int(t.planes.size());
  std::vector<float> scale(size_t(count - 1), 1e-6f);
  const auto& state = t.texels.state[page];
  for (size_t i = 0; i < state.size(); ++i) {
    if (state[i] == LightmapBake::Empty) continue;
    for (int c = 1; c < count; ++c)
      for (int ch = 0; ch < 3; ++ch) scale[size_t(c - 1)] = std::max(scale[size_t(c - 1)], std::abs(ratio(t, page, i, c, ch)));
  }
  return scale;
}

// Texture `k` of page `page`: numbers 4k .. 4k + 3 of the texel's ratios (coefficient 1 .. count-1,
// channel fastest), each over its coefficient's scale, row 0 at the top.
std::vector<uint8_t> ratioPng(const TransferBake& t, size_t page, int k, const std::vector<float>& scale) {
  const int s = t.texels.pageSize;
  const int count = int(t.planes.size());
  const int numbers = 3 * (count - 1);
  std::vector<uint8_t> rgba(size_t(s) * size_t(s) * 4, 128);
  for (int y = 0; y < s; ++y)
    for (int x = 0; x < s; ++x) {
      const size_t i = size_t(y) * size_t(s) + size_t(x);
      const size_t row = size_t(s - 1 - y);
      for (int slot = 0; slot < 4; ++slot) {
        const int v = 4 * k + slot;
        if (v >= numbers) break;
        const int coefficient = 1 + v / 3, channel = v % 3;
        const float q = ratio(t, page, i, coefficient, channel);
        const float packed = std::clamp(0.5f + 0.5f * q / scale[size_t(coefficient - 1)], 0.0f, 1.0f);
        rgba[(row * size_t(s) + size_t(x)) * 4 + size_t(slot)] = uint8_t(std::lround(packed * 255.0f));
      }
    }
  std::vector<uint8_t> png;
  if (!stbi_write_png_to_func(appendBytes, &png, s, s, 4, rgba.data(), s * 4))
    throw Error("cannot encode a transfer texture as PNG");
  return png;
}

}  // namespace

void addTransferLightmaps(GlbOptions& o, const Scene& scene, const LightmapAtlas& atlas, const TransferBake& transfer,
                          const LightmapBake& relit) {
  const size_t first = o.images.size();
  addLightmaps(o, scene, atlas, relit);
  const int count = int(transfer.planes.size());
  const int ratioTextures = (3 * (count - 1) + 3) / 4;
  o.transferBands = transfer.bands;
  o.transferImages.assign(o.images.size(), {});
  o.transferRatioScales.assign(o.images.size(), {});
  const size_t pages = transfer.planes.empty() ? 0 : transfer.planes[0].size();
  for (size_t img = first, end = o.images.size(); img < end; ++img) {
    // The pages addLightmaps wrote are named lightmapN after their page.
    const size_t page = size_t(std::stoul(o.images[img].name.substr(std::string("lightmap").size())));
    if (page >= pages) continue;
    Image band0(transfer.texels.pageSize, transfer.texels.pageSize);
    const int s = transfer.texels.pageSize;
    for (int y = 0; y < s; ++y)
      for (int x = 0; x < s; ++x) band0.at(x, s - 1 - y) = transfer.planes[0][page][size_t(y) * size_t(s) + size_t(x)];
    GlbImage g0;
    g0.name = fmt::format("lightmap{}_transfer0", page);
    g0.rgbmRange = rgbmRange(band0);
    g0.png = encodeRgbmPng(band0, g0.rgbmRange);
    o.transferImages[img].push_back(int32_t(o.images.size()));
    o.images.push_back(std::move(g0));
    const std::vector<float> scale = ratioScales(transfer, page);
    o.transferRatioScales[img] = scale;
    for (int k = 0; k < ratioTextures; ++k) {
      GlbImage g;
      g.name = fmt::format("lightmap{}_transfer_ratio{}", page, k);
      g.clamped = true;
      g.png = ratioPng(transfer, page, k, scale);
      o.transferImages[img].push_back(int32_t(o.images.size()));
      o.images.push_back(std::move(g));
    }
  }
  o.transferImages.resize(o.images.size());
  o.transferRatioScales.resize(o.images.size());
  if (!o.directionalMode.empty()) o.directionalImages.resize(o.images.size());
  // The light the fallback was relit with: skies as SH, suns as directions (a viewer turns them).
  Scene skies;
  skies.up = scene.up;
  for (const Light& l : scene.lights) {
    if (l.type == Light::Type::Sky || l.type == Light::Type::CieOvercastSky) skies.lights.push_back(l);
    if (l.type == Light::Type::Directional) o.transferSuns.push_back({glm::normalize(l.direction), l.power()});
  }
  o.transferSky = distantLightSh(skies, transfer.bands).coefficients;
}

}  // namespace luxel
