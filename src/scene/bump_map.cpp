#include "scene/bump_map.h"

#include <algorithm>

namespace luxel {

Texture normalMapFromHeight(const Texture& height, float multiplier) {
  Texture out;
  out.path = height.path;
  out.width = height.width;
  out.height = height.height;
  const size_t w = size_t(std::max(height.width, 0)), h = size_t(std::max(height.height, 0));
  if (height.texels.size() < w * h) return out;
  out.texels.resize(w * h);
  auto at = [&](size_t x, size_t y) {
    const Rgb& t = height.texels[y * w + x];
    return (t.r + t.g + t.b) * (1.0f / 3.0f);
  };
  // Rows are stored bottom first (v = 0 at row 0), so row + 1 is +v.
  for (size_t y = 0; y < h; ++y) {
    const size_t down = y == 0 ? h - 1 : y - 1, up = y + 1 == h ? 0 : y + 1;
    for (size_t x = 0; x < w; ++x) {
      const size_t left = x == 0 ? w - 1 : x - 1, right = x + 1 == w ? 0 : x + 1;
      const float dhdu = 0.5f * (at(right, y) - at(left, y)) * multiplier;
      const float dhdv = 0.5f * (at(x, up) - at(x, down)) * multiplier;
      const Vec3 n = glm::normalize(Vec3(-dhdu, -dhdv, 1.0f));
      out.texels[y * w + x] = 0.5f * n + 0.5f;
    }
  }
  return out;
}

bool looksLikeNormalMap(const Texture& texture) {
  if (texture.texels.empty()) return false;
  double spread = 0.0, blue = 0.0;
  for (const Rgb& t : texture.texels) {
    spread += std::max({t.r, t.g, t.b}) - std::min({t.r, t.g, t.b});
    blue += t.b;
  }
  const double n = double(texture.texels.size());
  return spread / n > 0.1 && blue / n > 0.6;
}

}  // namespace luxel
