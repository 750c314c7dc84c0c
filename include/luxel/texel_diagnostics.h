// What a lightmap bake would make of each texel, found before baking: which texels a face claims,
// which are claimed twice (overlapping UVs), which lie next to another chart's (bilinear filtering
// mixes the two charts' light: a leak or a seam that dilation cannot mend) and which see the
// inside of geometry (invalid: the bake throws their value away and fills them from their chart).
// The views of lightmappers' editors (Unity's UV Overlap and Invalid Texels, Bakery's checker)
// show the same; luxel view's texels view draws these (docs/viewer.md).
#pragma once

#include <cstdint>
#include <vector>

#include "luxel/lightmap.h"

namespace luxel {

struct TexelDiagnosticsOptions {
  // The bake's own validity test (LightmapBakeOptions): rays per texel and the share of back
  // faces they may hit. 0 rays: no texel is tested (none is invalid).
  int validityRays = 16;
  float maxBackfaceShare = 0.1f;
};

struct TexelDiagnostics {
  enum Flag : uint8_t {
    Covered = 1,      // a face claims it
    Overlap = 2,      // two faces or more claim it (UVs that overlap: their light is mixed)
    Bleed = 4,        // a texel of another chart is among its 8 neighbours (no gutter between)
    Invalid = 8,      // it sees back faces: inside geometry
  };
  int pageSize = 0;
  std::vector<std::vector<uint8_t>> flags;   // [page][y * pageSize + x], row 0 at v = 0; Flag bits
  std::vector<std::vector<uint32_t>> chart;  // [page][texel]: the chart of the first face claiming it, or kNoChart
  static constexpr uint32_t kNoChart = UINT32_MAX;
  size_t covered = 0, overlapping = 0, bleeding = 0, invalid = 0;  // texels with each flag
  double seconds = 0.0;
};

// Diagnoses an atlas (buildLightmapAtlas; AtlasOptions::keepOverlappingUvs lets given UVs that
// overlap through to be shown). Throws Error on absurd options.
TexelDiagnostics diagnoseTexels(const Scene& scene, const LightmapAtlas& atlas,
                                const TexelDiagnosticsOptions& options = {});

}  // namespace luxel
