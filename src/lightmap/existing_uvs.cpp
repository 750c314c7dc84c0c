// A mesh's own lightmap UVs (Mesh::lightmapUvs): checked, then used as they are.
#include <fmt/format.h>

#include <numeric>

#include "lightmap/atlas_internal.h"
#include "luxel/error.h"

namespace luxel::lightmap {

size_t useExistingUvs(const Scene& scene, uint32_t meshIndex, int pageSize, uint32_t page,
                      uint32_t firstChart, LightmapAtlas& atlas) {
  const Mesh& mesh = scene.meshes[meshIndex];
  const auto& uv = mesh.lightmapUvs;
  for (size_t i = 0; i < uv.size(); ++i)
    if (!(uv[i].x >= 0.0f && uv[i].x <= 1.0f && uv[i].y >= 0.0f && uv[i].y <= 1.0f))
      throw Error(fmt::format("scene '{}': mesh '{}': lightmap uv {} ({}, {}) is outside [0,1]",
                              scene.name, mesh.name, i, uv[i].x, uv[i].y));

  // Charts: faces joined by shared UV vertices.
  std::vector<uint32_t> parent(uv.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const Face& f : mesh.faces)
    for (int k = 1; k < f.vertexCount(); ++k) parent[find(f.v[size_t(k)])] = find(f.v[0]);
  std::vector<int64_t> chartOfRoot(uv.size(), -1);
  size_t charts = 0;

  // Every face rasterised at the page size: a texel centre inside two faces is an overlap.
  std::vector<uint32_t> owner(size_t(pageSize) * size_t(pageSize), UINT32_MAX);
  auto& out = atlas.faces[meshIndex];
  for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    int64_t& chart = chartOfRoot[find(face.v[0])];
    if (chart < 0) chart = int64_t(charts++);
    out[f].page = page;
    out[f].chart = firstChart + uint32_t(chart);
    for (int k = 0; k < 4; ++k) out[f].texel[size_t(k)] = uv[face.v[size_t(k)]] * float(pageSize);
    auto claim = [&](int x, int y) {
      uint32_t& o = owner[size_t(y) * size_t(pageSize) + size_t(x)];
      if (o != UINT32_MAX && o != f)
        throw Error(fmt::format(
            "scene '{}': mesh '{}': lightmap uvs of faces {} and {} overlap (texel {}, {} of {})",
            scene.name, mesh.name, o, f, x, y, pageSize));
      o = f;
    };
    const auto& t = out[f].texel;
    rasteriseTriangle(t[0], t[1], t[2], pageSize, claim);
    if (!face.isTriangle()) rasteriseTriangle(t[0], t[2], t[3], pageSize, claim);
  }
  return charts;
}

}  // namespace luxel::lightmap
