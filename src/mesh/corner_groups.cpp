#include "mesh/corner_groups.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace luxel {
namespace {

struct CornerKey {
  int64_t x, y, z;
  uint32_t element;
  int corner;
  bool samePlace(const CornerKey& o) const { return x == o.x && y == o.y && z == o.z; }
};

}  // namespace

CornerGroups::CornerGroups(const SurfaceSet& surfaces, float creaseCosine) {
  const auto& elements = surfaces.elements;
  // Corners closer than this are one vertex: far below any element size, far above float noise.
  const double cell = std::max(1e-6 * double(surfaces.sceneExtent), 1e-12);
  std::vector<CornerKey> keys;
  keys.reserve(elements.size() * 4);
  for (uint32_t e = 0; e < elements.size(); ++e) {
    const Polygon& poly = elements[e].polygon;
    for (int c = 0; c < poly.count; ++c) {
      const Vec3& p = poly.v[size_t(c)];
      keys.push_back({std::llround(p.x / cell), std::llround(p.y / cell), std::llround(p.z / cell), e, c});
    }
  }
  std::sort(keys.begin(), keys.end(), [](const CornerKey& a, const CornerKey& b) {
    return std::tie(a.x, a.y, a.z, a.element) < std::tie(b.x, b.y, b.z, b.element);
  });

  // Gather, for each (element, corner) slot, the compatible elements at the same place.
  std::vector<std::vector<uint32_t>> lists(elements.size() * 4);
  for (size_t begin = 0; begin < keys.size();) {
    size_t end = begin + 1;
    while (end < keys.size() && keys[end].samePlace(keys[begin])) ++end;
    for (size_t i = begin; i < end; ++i) {
      const Element& a = elements[keys[i].element];
      auto& list = lists[size_t(keys[i].element) * 4 + size_t(keys[i].corner)];
      for (size_t j = begin; j < end; ++j) {
        const Element& b = elements[keys[j].element];
        if (a.material == b.material && glm::dot(a.normal, b.normal) >= creaseCosine)
          list.push_back(keys[j].element);
      }
    }
    begin = end;
  }

  offsets_.resize(lists.size() + 1, 0);
  for (size_t s = 0; s < lists.size(); ++s) offsets_[s + 1] = offsets_[s] + uint32_t(lists[s].size());
  members_.reserve(offsets_.back());
  for (const auto& list : lists) members_.insert(members_.end(), list.begin(), list.end());
}

}  // namespace luxel
