#include "shadow_casters.h"

#include <array>
#include <unordered_map>

#include "core/position_key.h"

namespace luxel::viewer {

CasterMesh casterMesh(const SurfaceSet& surfaces) {
  CasterMesh out;
  std::unordered_map<PositionKey, uint32_t, PositionKeyHash> index;
  auto vertex = [&](Vec3 p) {
    const auto [it, fresh] = index.try_emplace(positionKey(p), uint32_t(out.vertices.size()));
    if (fresh) out.vertices.push_back(p + Vec3(0.0f));
    return it->second;
  };
  std::vector<std::array<uint32_t, 3>> triangles;
  for (const SurfaceFace& face : surfaces.faces) {
    const uint32_t a = vertex(face.corners[0]), b = vertex(face.corners[1]), c = vertex(face.corners[2]);
    triangles.push_back({a, b, c});
    if (!face.triangle) triangles.push_back({a, c, vertex(face.corners[3])});
  }
  // Directed edges p -> q: how many triangles run along each, and the third corner of the last.
  struct Use {
    uint32_t count = 0, third = 0;
  };
  std::unordered_map<uint64_t, Use> edges;
  auto key = [](uint32_t p, uint32_t q) { return uint64_t(p) << 32 | q; };
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      Use& u = edges[key(t[size_t(k)], t[size_t((k + 1) % 3)])];
      ++u.count, u.third = t[size_t((k + 2) % 3)];
    }
  out.adjacency.reserve(triangles.size() * 6);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const uint32_t p = t[size_t(k)], q = t[size_t((k + 1) % 3)], own = t[size_t((k + 2) % 3)];
      const auto back = edges.find(key(q, p));
      const bool paired = p != q && back != edges.end() && back->second.count == 1 && edges.at(key(p, q)).count == 1;
      out.adjacency.push_back(p);
      out.adjacency.push_back(paired ? back->second.third : own);
    }
  return out;
}

}  // namespace luxel::viewer
