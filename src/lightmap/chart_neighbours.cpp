// Texels next to another chart's: what bilinear filtering mixes across charts.
#include "lightmap/atlas_internal.h"

namespace luxel::lightmap {

std::vector<uint8_t> nextToAnotherChart(const std::vector<uint32_t>& chart, int size) {
  std::vector<uint8_t> next(chart.size(), 0);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const size_t i = size_t(y) * size_t(size) + size_t(x);
      if (chart[i] == kNoChart) continue;
      for (int dy = -1; dy <= 1 && !next[i]; ++dy)
        for (int dx = -1; dx <= 1 && !next[i]; ++dx) {
          const int xx = x + dx, yy = y + dy;
          if (xx < 0 || yy < 0 || xx >= size || yy >= size) continue;
          const uint32_t other = chart[size_t(yy) * size_t(size) + size_t(xx)];
          next[i] = other != kNoChart && other != chart[i];
        }
    }
  return next;
}

}  // namespace luxel::lightmap
