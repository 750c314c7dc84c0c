#include "mesh/corner_groups.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

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
  // Keys at one place are one run after sorting; ties by element keep each run's order fixed.
  tbb::parallel_sort(keys.begin(), keys.end(), [](const CornerKey& a, const CornerKey& b) {
    return std::tie(a.x, a.y, a.z, a.element) < std::tie(b.x, b.y, b.z, b.element);
  });
  std::vector<size_t> runs;  // where each run of keys at one place begins
  for (size_t i = 0; i < keys.size(); ++i)
    if (i == 0 || !keys[i].samePlace(keys[i - 1])) runs.push_back(i);
  runs.push_back(keys.size());

  // For each (element, corner) slot, the compatible elements at the same place, in a count pass
  // and a fill pass straight into the flat arrays (a list per slot was four allocations an
  // element, the bulk of this at a million elements). A slot belongs to one key, so the runs
  // fill in parallel.
  auto compatible = [&](const Element& a, const Element& b) {
    return a.material == b.material && glm::dot(a.normal, b.normal) >= creaseCosine;
  };
  auto slotOf = [&](const CornerKey& k) { return size_t(k.element) * 4 + size_t(k.corner); };
  offsets_.assign(elements.size() * 4 + 1, 0);
  const size_t runCount = runs.size() - 1;
  tbb::parallel_for(size_t(0), runCount, [&](size_t r) {
    for (size_t i = runs[r]; i < runs[r + 1]; ++i) {
      const Element& a = elements[keys[i].element];
      uint32_t count = 0;
      for (size_t j = runs[r]; j < runs[r + 1]; ++j) count += compatible(a, elements[keys[j].element]) ? 1 : 0;
      offsets_[slotOf(keys[i]) + 1] = count;
    }
  });
  for (size_t s = 1; s < offsets_.size(); ++s) offsets_[s] += offsets_[s - 1];
  members_.resize(offsets_.back());
  tbb::parallel_for(size_t(0), runCount, [&](size_t r) {
    for (size_t i = runs[r]; i < runs[r + 1]; ++i) {
      const Element& a = elements[keys[i].element];
      uint32_t* out = members_.data() + offsets_[slotOf(keys[i])];
      for (size_t j = runs[r]; j < runs[r + 1]; ++j)
        if (compatible(a, elements[keys[j].element])) *out++ = keys[j].element;
    }
  });
}

}  // namespace luxel
