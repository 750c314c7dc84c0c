// Packing charts onto pages: each chart turned to its principal axes, scaled to the density, and
// placed in a shelf (next fit, tallest first) on whole texels with `gutter` empty texels between
// charts and along the page's border.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "lightmap/atlas_internal.h"

namespace luxel::lightmap {
namespace {

// A chart turned so its longer principal axis runs along u, and its bounds (metres).
struct Oriented {
  glm::mat2 rotation{1.0f};
  Vec2 lo{0.0f}, size{0.0f};
};

Oriented orient(const Chart& chart) {
  Vec2 mean(0.0f);
  size_t n = 0;
  for (const auto& t : chart.uv)
    for (Vec2 p : t) mean += p, ++n;
  mean /= float(std::max<size_t>(n, 1));
  double sxx = 0, syy = 0, sxy = 0;
  for (const auto& t : chart.uv)
    for (Vec2 p : t) {
      Vec2 d = p - mean;
      sxx += d.x * d.x, syy += d.y * d.y, sxy += d.x * d.y;
    }
  float angle = float(0.5 * std::atan2(2.0 * sxy, sxx - syy));
  float c = std::cos(angle), s = std::sin(angle);
  Oriented o;
  o.rotation = glm::mat2(c, -s, s, c);  // column-major: rotates by -angle, the axis onto u
  Vec2 lo(INFINITY), hi(-INFINITY);
  for (const auto& t : chart.uv)
    for (Vec2 p : t) lo = glm::min(lo, o.rotation * p), hi = glm::max(hi, o.rotation * p);
  if (n == 0) lo = hi = Vec2(0.0f);
  if (hi.y - lo.y > hi.x - lo.x) {  // keep the longer side along u: shelves stay low
    o.rotation = glm::mat2(0, 1, -1, 0) * o.rotation;  // (x, y) -> (-y, x)
    Vec2 lo2(-hi.y, lo.x), hi2(-lo.y, hi.x);
    lo = lo2, hi = hi2;
  }
  o.lo = lo;
  o.size = hi - lo;
  return o;
}

PackResult pack(const std::vector<Chart>& charts, float density, const AtlasOptions& options,
                uint32_t firstPage, uint32_t firstChart, LightmapAtlas* atlas) {
  const int page = options.pageSize, g = options.gutter;
  const float avail = float(page - 2 * g);
  struct Item {
    Oriented o;
    float scale;  // texels per metre of this chart
    int w, h;
  };
  PackResult result;
  std::vector<Item> items(charts.size());
  for (size_t i = 0; i < charts.size(); ++i) {
    Item& it = items[i];
    it.o = orient(charts[i]);
    it.scale = density;
    float longest = std::max(it.o.size.x, it.o.size.y) * density;
    if (std::ceil(longest) > avail) {
      // Larger than a page: scaled down to one texel less than the page's free width.
      it.scale = (avail - 1.0f) / std::max(it.o.size.x, it.o.size.y);
      ++result.scaledDown;
    }
    it.w = std::max(1, int(std::ceil(it.o.size.x * it.scale)));
    it.h = std::max(1, int(std::ceil(it.o.size.y * it.scale)));
  }
  std::vector<size_t> order(items.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return items[a].h != items[b].h ? items[a].h > items[b].h : items[a].w > items[b].w;
  });
  int pages = 0, x = 0, y = 0, shelf = 0;
  for (size_t i : order) {
    const Item& it = items[i];
    if (pages == 0 || x + it.w > page - g) {  // next shelf
      x = g;
      y += shelf + (pages == 0 ? 0 : g);
      shelf = 0;
      if (pages == 0 || y + it.h > page - g) {  // next page
        ++pages;
        y = g;
      }
    }
    if (atlas) {
      const Chart& chart = charts[i];
      for (size_t k = 0; k < chart.faces.size(); ++k) {
        LightmapAtlas::FaceUv& out = atlas->faces[chart.mesh][chart.faces[k]];
        out.page = firstPage + uint32_t(pages - 1);
        out.chart = firstChart + uint32_t(i);
        for (int c = 0; c < 4; ++c)
          out.texel[size_t(c)] =
              (it.o.rotation * chart.uv[k][size_t(c)] - it.o.lo) * it.scale + Vec2(float(x), float(y));
      }
    }
    x += it.w + g;
    shelf = std::max(shelf, it.h);
  }
  result.pages = pages;
  return result;
}

}  // namespace

PackResult packCharts(const std::vector<Chart>& charts, float density, const AtlasOptions& options,
                      uint32_t firstPage, uint32_t firstChart, LightmapAtlas* atlas) {
  return pack(charts, density, options, firstPage, firstChart, atlas);
}

int pagesNeeded(const std::vector<Chart>& charts, float density, const AtlasOptions& options) {
  PackResult r = pack(charts, density, options, 0, 0, nullptr);
  return r.scaledDown > 0 ? std::numeric_limits<int>::max() : r.pages;
}

}  // namespace luxel::lightmap
