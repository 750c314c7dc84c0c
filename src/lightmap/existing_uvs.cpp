// A mesh's own lightmap UVs (Mesh::lightmapUvs): checked, then used as they are.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <string>
#include <vector>

#include "lightmap/atlas_internal.h"
#include "luxel/error.h"

namespace luxel::lightmap {

std::string degenerateGivenUvs(const Scene& scene, uint32_t meshIndex) {
  const Mesh& mesh = scene.meshes[meshIndex];
  const auto& uv = mesh.lightmapUvs;
  auto uvArea = [&](uint32_t a, uint32_t b, uint32_t c) {
    const Vec2 e1 = uv[b] - uv[a], e2 = uv[c] - uv[a];
    return 0.5 * std::abs(double(e1.x) * e2.y - double(e1.y) * e2.x);
  };
  auto area = [&](uint32_t a, uint32_t b, uint32_t c) {
    return 0.5 * double(glm::length(glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a])));
  };
  std::vector<double> faceArea(mesh.faces.size()), faceUvArea(mesh.faces.size());
  double total = 0.0, totalUv = 0.0;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& face = mesh.faces[f];
    faceArea[f] = area(face.v[0], face.v[1], face.v[2]) + (face.isTriangle() ? 0.0 : area(face.v[0], face.v[2], face.v[3]));
    faceUvArea[f] = uvArea(face.v[0], face.v[1], face.v[2]) + (face.isTriangle() ? 0.0 : uvArea(face.v[0], face.v[2], face.v[3]));
    total += faceArea[f];
    totalUv += faceUvArea[f];
  }
  if (!(total > 0.0)) return "";  // nothing to light: the checks of useExistingUvs are enough
  // A face is collapsed when its UVs hold under 1/10,000 of the UV area its surface would get at
  // the mesh's mean density. Engines' unwrappers collapse hidden faces (under a prop) on purpose,
  // so a few are fine; most of the surface collapsed (every UV at (0,0), a channel exported empty)
  // is not a lightmap layout.
  double collapsedArea = 0.0;
  size_t collapsed = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    if (faceUvArea[f] <= 1e-4 * totalUv * faceArea[f] / total && faceArea[f] > 0.0) collapsedArea += faceArea[f], ++collapsed;
  if (collapsedArea <= 0.5 * total) return "";
  return fmt::format("scene '{}': mesh '{}': its lightmap uvs have no area on {} of its {} faces ({:.0f}% of its "
                     "surface; uv area {:.3g} in all), which would bake black: unwrapped by luxel instead",
                     scene.name, mesh.name, collapsed, mesh.faces.size(), 100.0 * collapsedArea / total, totalUv);
}

size_t useExistingUvs(const Scene& scene, std::span<const uint32_t> meshes, int pageSize, uint32_t page,
                      uint32_t firstChart, bool keepOverlaps, LightmapAtlas& atlas) {
  // Every face of the page's meshes rasterised at the page size: a texel centre inside two faces
  // is an overlap, within a mesh or between meshes that share the page. A texel's owner is a
  // face's place among the page's faces (4 bytes a texel: a 16384^2 page is 1 GiB of them).
  constexpr uint32_t kFree = UINT32_MAX;
  size_t faces = 0;
  for (uint32_t m : meshes) faces += scene.meshes[m].faces.size();
  if (faces >= size_t(kFree))
    throw Error(fmt::format("scene '{}': {} faces on one lightmap page are too many", scene.name, faces));
  std::vector<uint32_t> firstFace(meshes.size() + 1, 0);  // the page's faces, mesh by mesh
  for (size_t k = 0; k < meshes.size(); ++k) firstFace[k + 1] = firstFace[k] + uint32_t(scene.meshes[meshes[k]].faces.size());
  auto ownerMesh = [&](uint32_t o) {  // the place in `meshes` of the mesh whose face owns o
    return size_t(std::upper_bound(firstFace.begin(), firstFace.end(), o) - firstFace.begin()) - 1;
  };
  std::vector<uint32_t> owner(size_t(pageSize) * size_t(pageSize), kFree);
  size_t charts = 0;
  for (size_t slot = 0; slot < meshes.size(); ++slot) {
    const uint32_t meshIndex = meshes[slot];
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

    auto& out = atlas.faces[meshIndex];
    for (uint32_t f = 0; f < mesh.faces.size(); ++f) {
      const Face& face = mesh.faces[f];
      int64_t& chart = chartOfRoot[find(face.v[0])];
      if (chart < 0) chart = int64_t(charts++);
      out[f].page = page;
      out[f].chart = firstChart + uint32_t(chart);
      for (int k = 0; k < 4; ++k) out[f].texel[size_t(k)] = uv[face.v[size_t(k)]] * float(pageSize);
      const uint32_t self = firstFace[slot] + f;
      auto claim = [&](int x, int y) {
        uint32_t& o = owner[size_t(y) * size_t(pageSize) + size_t(x)];
        if (o != kFree && o != self && keepOverlaps) return;  // the first face keeps it, as the bake does
        if (o != kFree && o != self) {
          const size_t otherSlot = ownerMesh(o);
          const uint32_t otherMesh = meshes[otherSlot], otherFace = o - firstFace[otherSlot];
          if (otherMesh == meshIndex)
            throw Error(fmt::format(
                "scene '{}': mesh '{}': lightmap uvs of faces {} and {} overlap (texel {}, {} of {})",
                scene.name, mesh.name, otherFace, f, x, y, pageSize));
          throw Error(fmt::format("scene '{}': lightmap uvs of mesh '{}' face {} and mesh '{}' face {} overlap on "
                                  "their shared page (texel {}, {} of {})",
                                  scene.name, scene.meshes[otherMesh].name, otherFace, mesh.name, f, x, y, pageSize));
        }
        o = self;
      };
      const auto& t = out[f].texel;
      rasteriseTriangle(t[0], t[1], t[2], pageSize, claim);
      if (!face.isTriangle()) rasteriseTriangle(t[0], t[2], t[3], pageSize, claim);
    }
  }

  // Charts with no gutter between them: their light mixes under bilinear filtering.
  std::vector<uint32_t> chartOf(owner.size(), kNoChart);
  for (size_t i = 0; i < owner.size(); ++i)
    if (owner[i] != kFree) {
      const size_t slot = ownerMesh(owner[i]);
      chartOf[i] = atlas.faces[meshes[slot]][owner[i] - firstFace[slot]].chart;
    }
  const std::vector<uint8_t> next = nextToAnotherChart(chartOf, pageSize);
  const auto bleeding = size_t(std::count(next.begin(), next.end(), uint8_t(1)));
  if (bleeding > 0) {
    std::string names;
    for (uint32_t m : meshes) names += (names.empty() ? "'" : ", '") + scene.meshes[m].name + "'";
    atlas.warnings.push_back(fmt::format(
        "scene '{}': {} {}: {} texels of {} lightmap uvs lie next to another chart's with no gutter at {} texels a "
        "side: bilinear filtering mixes the two charts' light there (leave a texel or two between charts; luxel view's "
        "texels view shows where)",
        scene.name, meshes.size() == 1 ? "mesh" : "meshes", names, bleeding, meshes.size() == 1 ? "its" : "their",
        pageSize));
  }
  return charts;
}

}  // namespace luxel::lightmap
