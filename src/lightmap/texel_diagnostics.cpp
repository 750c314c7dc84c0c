// diagnoseTexels (luxel/texel_diagnostics.h): the bake's own texel layout and validity test
// (prepareTexels), read back per texel. No library does this: it is the bake's view of its atlas.
#include "luxel/texel_diagnostics.h"

#include <chrono>

#include "lightmap/atlas_internal.h"
#include "lightmap/bake_steps.h"

namespace luxel {

TexelDiagnostics diagnoseTexels(const Scene& scene, const LightmapAtlas& atlas, const TexelDiagnosticsOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  LightmapBakeOptions bakeOptions;
  bakeOptions.validityRays = options.validityRays;
  bakeOptions.maxBackfaceShare = options.maxBackfaceShare;
  const LightmapBake bake = lightmap::prepareTexels(scene, atlas, bakeOptions);
  const SurfaceSet& set = bake.surfaces.surfaces;

  TexelDiagnostics d;
  d.pageSize = atlas.pageSize;
  const size_t n = size_t(atlas.pageSize) * size_t(atlas.pageSize);
  d.flags.assign(size_t(atlas.pageCount), std::vector<uint8_t>(n, 0));
  d.chart.assign(size_t(atlas.pageCount), std::vector<uint32_t>(n, TexelDiagnostics::kNoChart));
  // Every element is the one face's claim on its texel; a texel whose centre another face holds
  // too is contested (faces of one chart never both hold a centre: the top-left rule).
  for (size_t e = 0; e < set.elements.size(); ++e) {
    const auto& t = bake.surfaces.texels[e];
    const size_t i = size_t(t.y) * size_t(atlas.pageSize) + t.x;
    d.chart[t.page][i] = bake.surfaces.faceChart[set.elements[e].face];
    d.flags[t.page][i] |= TexelDiagnostics::Covered | (bake.valid[e] ? 0 : TexelDiagnostics::Invalid);
  }
  for (const auto& t : bake.surfaces.contested)
    d.flags[t.page][size_t(t.y) * size_t(atlas.pageSize) + t.x] |= TexelDiagnostics::Overlap;
  static_assert(TexelDiagnostics::kNoChart == lightmap::kNoChart);
  for (size_t p = 0; p < d.flags.size(); ++p) {
    const std::vector<uint8_t> next = lightmap::nextToAnotherChart(d.chart[p], atlas.pageSize);
    for (size_t i = 0; i < next.size(); ++i)
      if (next[i]) d.flags[p][i] |= TexelDiagnostics::Bleed;
  }
  for (const auto& page : d.flags)
    for (uint8_t f : page) {
      d.covered += (f & TexelDiagnostics::Covered) != 0;
      d.overlapping += (f & TexelDiagnostics::Overlap) != 0;
      d.bleeding += (f & TexelDiagnostics::Bleed) != 0;
      d.invalid += (f & TexelDiagnostics::Invalid) != 0;
    }
  d.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return d;
}

}  // namespace luxel
