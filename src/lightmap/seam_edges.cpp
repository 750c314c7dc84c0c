// overlappingEdges (seam_edges.h): a multi-level spatial hash over edge boxes, then the exact
// collinear-overlap test on the candidates.
#include "lightmap/seam_edges.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace luxel::lightmap {

bool edgesOverlap(const SeamEdge& e0, const SeamEdge& e1, float eps, float* s0, float* s1) {
  const Vec3 d = e0.b - e0.a;
  const float len = glm::length(d);
  if (len <= eps) return false;
  const Vec3 u = d / len;
  // Collinear: both ends of e1 on e0's line.
  auto off = [&](Vec3 p) { return glm::length(glm::cross(p - e0.a, u)); };
  if (off(e1.a) > eps || off(e1.b) > eps) return false;
  const float ta = glm::dot(e1.a - e0.a, u), tb = glm::dot(e1.b - e0.a, u);
  *s0 = std::max(0.0f, std::min(ta, tb));
  *s1 = std::min(len, std::max(ta, tb));
  return *s1 - *s0 > eps;
}

namespace {

uint64_t mix(uint64_t h, uint64_t v) {  // splitmix64 step over the running hash
  h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
  h ^= h >> 30, h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 27, h *= 0x94D049BB133111EBull;
  return h ^ (h >> 31);
}

// Distinct cells may share a key (a hash collision): that only adds candidates, which the exact
// test then rejects.
uint64_t cellKey(int level, int64_t x, int64_t y, int64_t z) {
  return mix(mix(mix(uint64_t(level), uint64_t(x)), uint64_t(y)), uint64_t(z));
}

}  // namespace

std::vector<EdgeOverlap> overlappingEdges(const std::vector<SeamEdge>& edges, float eps) {
  const size_t n = edges.size();
  std::vector<EdgeOverlap> result;
  if (n < 2) return result;
  const double grow = 2.0 * double(std::max(eps, 0.0f));  // beyond eps: the test's own rounding

  // Boxes, their sizes and the grid origin. Edges with non-finite ends match nothing.
  std::vector<glm::dvec3> lo(n), hi(n);
  std::vector<double> size(n);
  std::vector<uint8_t> usable(n, 1);
  glm::dvec3 origin(std::numeric_limits<double>::max());
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 a(edges[i].a), b(edges[i].b);
    if (!std::isfinite(a.x + a.y + a.z + b.x + b.y + b.z)) {
      usable[i] = 0;
      continue;
    }
    lo[i] = glm::min(a, b) - grow;
    hi[i] = glm::max(a, b) + grow;
    const glm::dvec3 s = hi[i] - lo[i];
    size[i] = std::max({s.x, s.y, s.z});
    origin = glm::min(origin, lo[i]);
  }
  // The finest cells are as large as the smallest box (at least 4 eps across), so that small
  // edges in dense detail do not crowd into cells sized for the typical edge; at most 40 levels,
  // which also bounds the cell indices.
  double base = std::numeric_limits<double>::max(), largest = 0.0;
  for (size_t i = 0; i < n; ++i)
    if (usable[i]) base = std::min(base, size[i]), largest = std::max(largest, size[i]);
  if (largest == 0.0)
    return result;  // no usable edge, or zero-length edges only (eps 0): no overlaps
  base = std::max(base, std::ldexp(largest, -40));

  // Level of an edge: the finest whose cells are at least as large as its box, so the box
  // touches at most 2 cells per axis there and at every coarser level; but no coarser than `top`,
  // about twice the median box (Sibenik: fastest there). Longer edges lie in the cells along
  // them at that level: a long edge in a huge cell would be a candidate of every short edge in it.
  std::vector<int> level(n, 0);
  std::vector<int> levels;
  int maxLevel = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!usable[i]) continue;
    int l = 0;
    while (std::ldexp(base, l) < size[i]) ++l;
    level[i] = l;
    levels.push_back(l);
    maxLevel = std::max(maxLevel, l);
  }
  std::nth_element(levels.begin(), levels.begin() + ptrdiff_t(levels.size() / 2), levels.end());
  // Within 2^20 of the longest edge, which bounds the pieces a long edge is cut into.
  const int top = std::min(maxLevel, std::max(levels[levels.size() / 2] + 1, maxLevel - 20));
  std::vector<uint8_t> populated(size_t(top) + 1, 0);
  for (size_t i = 0; i < n; ++i)
    if (usable[i]) level[i] = std::min(level[i], top), populated[size_t(level[i])] = 1;

  // The cells at level l that the segment of edge i, grown by `grow` (and a hair for rounding),
  // passes through: a slab test per cell of its box, or of each piece of it no longer than a cell.
  auto forCells = [&](size_t i, int l, std::vector<uint64_t>& keys) {
    keys.clear();
    const double cell = std::ldexp(base, l);
    const glm::dvec3 a(edges[i].a), b(edges[i].b);
    const double margin = grow + 1e-9 * cell;
    auto touches = [&](glm::dvec3 c) {  // the segment against cell c grown by margin
      const glm::dvec3 lo3 = origin + c * cell - margin, hi3 = origin + (c + 1.0) * cell + margin;
      double t0 = 0.0, t1 = 1.0;
      for (int k = 0; k < 3; ++k) {
        const double d = b[k] - a[k];
        if (d == 0.0) {
          if (a[k] < lo3[k] || a[k] > hi3[k]) return false;
          continue;
        }
        double u = (lo3[k] - a[k]) / d, v = (hi3[k] - a[k]) / d;
        if (u > v) std::swap(u, v);
        t0 = std::max(t0, u), t1 = std::min(t1, v);
        if (t0 > t1) return false;
      }
      return true;
    };
    const double length = glm::length(b - a);
    const int pieces = std::max(1, int(std::ceil(length / cell)));
    for (int p = 0; p < pieces; ++p) {
      const glm::dvec3 pa = a + (b - a) * (double(p) / pieces),
                       pb = a + (b - a) * (double(p + 1) / pieces);
      const glm::dvec3 c0 = glm::floor((glm::min(pa, pb) - margin - origin) / cell),
                       c1 = glm::floor((glm::max(pa, pb) + margin - origin) / cell);
      for (double z = c0.z; z <= c1.z; ++z)
        for (double y = c0.y; y <= c1.y; ++y)
          for (double x = c0.x; x <= c1.x; ++x)
            if (touches(glm::dvec3(x, y, z)))
              keys.push_back(cellKey(l, int64_t(x), int64_t(y), int64_t(z)));
    }
    if (pieces > 1) {
      std::sort(keys.begin(), keys.end());
      keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    }
  };

  // Buckets: (key, edge) sorted by key, and each key's range.
  std::vector<std::pair<uint64_t, uint32_t>> entries;
  entries.reserve(n * 4);
  std::vector<uint64_t> keys;
  for (size_t i = 0; i < n; ++i) {
    if (!usable[i]) continue;
    forCells(i, level[i], keys);
    for (uint64_t key : keys) entries.emplace_back(key, uint32_t(i));
  }
  std::sort(entries.begin(), entries.end());
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> buckets;
  buckets.reserve(entries.size());
  for (size_t k = 0; k < entries.size();) {
    size_t e = k;
    while (e < entries.size() && entries[e].first == entries[k].first) ++e;
    buckets.emplace(entries[k].first, std::pair<uint32_t, uint32_t>(uint32_t(k), uint32_t(e)));
    k = e;
  }

  std::vector<Vec3> dir(n, Vec3(0.0f));  // unit directions (zero for zero-length edges)
  std::vector<float> len(n, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    len[i] = glm::length(edges[i].b - edges[i].a);
    if (len[i] > 0.0f) dir[i] = (edges[i].b - edges[i].a) / len[i];
  }
  // Each unordered pair is looked up from one side only: the edge at the finer level, or the lower
  // index at the same level.
  constexpr size_t kBlock = 1024;
  const size_t blocks = (n + kBlock - 1) / kBlock;
  std::vector<std::vector<EdgeOverlap>> found(blocks);
  tbb::parallel_for(size_t(0), blocks, [&](size_t blk) {
    std::vector<uint32_t> candidates;
    std::vector<uint64_t> keys;
    for (size_t i = blk * kBlock; i < std::min(n, (blk + 1) * kBlock); ++i) {
      if (!usable[i]) continue;
      candidates.clear();
      for (int l = level[i]; l <= top; ++l) {
        if (!populated[size_t(l)]) continue;
        forCells(i, l, keys);
        for (uint64_t key : keys) {
          const auto it = buckets.find(key);
          if (it == buckets.end()) continue;
          for (uint32_t k = it->second.first; k < it->second.second; ++k) {
            const uint32_t j = entries[k].second;
            if (level[j] != l || (l == level[i] && j <= i) || edges[j].face == edges[i].face)
              continue;
            // Overlapping edges are parallel: the second's ends lie within eps of the first's
            // line, so its extent across that line is at most 2 eps (more for rounding).
            const size_t f = std::min<size_t>(i, j), g = std::max<size_t>(i, j);
            if (glm::length(glm::cross(dir[f], edges[g].b - edges[g].a)) >
                2.5f * eps + 1e-6f * (len[f] + len[g]))
              continue;
            candidates.push_back(j);
          }
        }
      }
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
      for (uint32_t j : candidates) {
        const auto first = uint32_t(std::min<size_t>(i, j)),
                   second = uint32_t(std::max<size_t>(i, j));
        EdgeOverlap o{first, second, 0.0f, 0.0f};
        if (edgesOverlap(edges[first], edges[second], eps, &o.s0, &o.s1)) found[blk].push_back(o);
      }
    }
  });
  for (auto& f : found) result.insert(result.end(), f.begin(), f.end());
  std::sort(result.begin(), result.end(), [](const EdgeOverlap& x, const EdgeOverlap& y) {
    return x.first != y.first ? x.first < y.first : x.second < y.second;
  });
  return result;
}

}  // namespace luxel::lightmap
