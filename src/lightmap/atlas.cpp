// buildLightmapAtlas (lightmap.h): options, the per-mesh choice between given and generated UVs,
// the density, and the conservative-rasterisation flags.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include "lightmap/atlas_internal.h"
#include "luxel/error.h"

namespace luxel {

namespace {

void checkOptions(const AtlasOptions& o) {
  if (o.pageSize < 16 || o.pageSize > 16384)
    throw Error(fmt::format("lightmap atlas: page size {} is outside 16..16384", o.pageSize));
  if (o.gutter < 0 || o.gutter > o.pageSize / 4)
    throw Error(fmt::format("lightmap atlas: gutter {} is outside 0..{} (a quarter of the page)",
                            o.gutter, o.pageSize / 4));
  if (!std::isfinite(o.texelsPerMetre) || o.texelsPerMetre < 0.0f)
    throw Error(fmt::format("lightmap atlas: texels per metre {} is negative or not finite",
                            o.texelsPerMetre));
  if (o.sizePagesToContent && !(o.texelsPerMetre > 0.0f))
    throw Error("lightmap atlas: pages sized to their content need a density (texelsPerMetre > 0)");
  if (!(o.chartAngle > 0.0f && o.chartAngle <= 180.0f))
    throw Error(fmt::format("lightmap atlas: chart angle {} is outside (0, 180] degrees",
                            o.chartAngle));
}

// The largest density at which every chart fits on one page (no chart scaled down), by bisection
// in log space between the area bound (all of a page covered) and a thousandth of it.
float fitDensity(const std::vector<lightmap::Chart>& charts, double area, const AtlasOptions& o) {
  double free = double(o.pageSize - 2 * o.gutter);
  double hi = std::sqrt(free * free / std::max(area, 1e-30)), lo = hi * 1e-3;
  if (lightmap::pagesNeeded(charts, float(lo), o) > 1)
    throw Error(fmt::format("lightmap atlas: {} charts do not fit on one {} x {} page even at {:.3g} "
                            "texels per metre; give texelsPerMetre or a larger page",
                            charts.size(), o.pageSize, o.pageSize, lo));
  for (int i = 0; i < 30 && hi / lo > 1.0001; ++i) {
    double mid = std::sqrt(lo * hi);
    (lightmap::pagesNeeded(charts, float(mid), o) == 1 ? lo : hi) = mid;
  }
  return float(lo);
}

}  // namespace

LightmapAtlas buildLightmapAtlas(const Scene& scene, const AtlasOptions& options) {
  checkOptions(options);
  scene.validate();
  if (!options.givenUvPages.empty() && options.givenUvPages.size() != scene.meshes.size())
    throw Error(fmt::format("lightmap atlas: {} shared pages given for the {} meshes of scene '{}'",
                            options.givenUvPages.size(), scene.meshes.size(), scene.name));
  AtlasOptions o = options;  // with the page size chosen below
  LightmapAtlas atlas;
  atlas.faces.resize(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m) atlas.faces[m].resize(scene.meshes[m].faces.size());

  // Per mesh: keep its own UVs? Not when they have no area: they would bake black.
  std::vector<uint8_t> given(scene.meshes.size(), 0);
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (!options.useMeshUvs || mesh.lightmapUvs.empty() || mesh.faces.empty()) continue;
    const std::string degenerate = lightmap::degenerateGivenUvs(scene, m);
    if (degenerate.empty()) given[m] = 1;
    else atlas.warnings.push_back(degenerate);
  }

  // Meshes without their own UVs: charts, flattened, then packed together (below).
  std::vector<lightmap::Chart> charts;
  double area = 0.0;
  const float maxAngle = options.chartAngle * std::numbers::pi_v<float> / 180.0f;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    if (given[m] || mesh.faces.empty()) continue;
    lightmap::WeldedMesh w = lightmap::weld(mesh);
    for (float a : w.area) area += a;
    auto flat = lightmap::parameterise(w, lightmap::segmentCharts(w, m, maxAngle));
    for (auto& c : flat) charts.push_back(std::move(c));
  }
  const bool givenUvs = std::find(given.begin(), given.end(), 1) != given.end();
  if (options.sizePagesToContent && !givenUvs && !charts.empty()) {
    // The smallest power of two that needs no more pages (pagesNeeded counts a page that would
    // scale a chart down as needing infinitely many: then the largest page stays).
    const int most = lightmap::pagesNeeded(charts, options.texelsPerMetre, options);
    for (int size = 16; size < options.pageSize && most != std::numeric_limits<int>::max(); size *= 2) {
      AtlasOptions smaller = options;
      smaller.pageSize = size;
      if (smaller.gutter > size / 4) continue;
      if (lightmap::pagesNeeded(charts, options.texelsPerMetre, smaller) <= most) {
        o.pageSize = size;
        break;
      }
    }
  }
  atlas.pageSize = o.pageSize;

  // Meshes with their own UVs first, as given: the pages they say they share, in the order of
  // their numbers (a baked glb's pages keep their order), then a page for each other mesh.
  std::map<int, std::vector<uint32_t>> shared;  // a shared page's number -> its meshes
  std::vector<std::vector<uint32_t>> givenPages;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    if (!given[m]) continue;
    const int number = m < options.givenUvPages.size() ? options.givenUvPages[m] : -1;
    if (number >= 0) shared[number].push_back(m);
  }
  for (auto& [number, meshes] : shared) givenPages.push_back(std::move(meshes));
  for (uint32_t m = 0; m < scene.meshes.size(); ++m)
    if (given[m] && !(m < options.givenUvPages.size() && options.givenUvPages[m] >= 0)) givenPages.push_back({m});
  uint32_t page = 0;
  for (const std::vector<uint32_t>& meshes : givenPages)
    atlas.chartCount += lightmap::useExistingUvs(scene, meshes, o.pageSize, page++, uint32_t(atlas.chartCount),
                                                 options.keepOverlappingUvs, atlas);
  if (!charts.empty()) {
    float density = o.texelsPerMetre > 0.0f ? o.texelsPerMetre : fitDensity(charts, area, o);
    auto packed = lightmap::packCharts(charts, density, o, page, uint32_t(atlas.chartCount), &atlas);
    atlas.texelsPerMetre = density;
    atlas.chartCount += charts.size();
    page += uint32_t(packed.pages);
  }
  atlas.pageCount = int(page);

  // Faces that hold no texel centre are flagged for conservative rasterisation.
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    for (size_t f = 0; f < scene.meshes[m].faces.size(); ++f) {
      auto& uv = atlas.faces[m][f];
      bool hit = false;
      auto any = [&](int, int) { hit = true; };
      lightmap::rasteriseTriangle(uv.texel[0], uv.texel[1], uv.texel[2], o.pageSize, any);
      if (!scene.meshes[m].faces[f].isTriangle())
        lightmap::rasteriseTriangle(uv.texel[0], uv.texel[2], uv.texel[3], o.pageSize, any);
      uv.conservative = !hit;
    }
  return atlas;
}

}  // namespace luxel
