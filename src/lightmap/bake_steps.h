// The steps every texel bake shares (src/lightmap/lightmap_bake.cpp): the texels as elements with
// their validity, and, once each texel has its values, filling invalid texels from their chart,
// stitching seams and dilating into the gutters. bakeLightmaps solves for irradiance between the
// two; bakeTransfer (transfer_bake.cpp) shoots transfer functions.
#pragma once

#include <functional>
#include <vector>

#include "luxel/lightmap.h"

namespace luxel::lightmap {

// A bake with its pageSize, texel surfaces and validity set (invalid texels' areas shrunk so that
// they take no part in their patch's mean), and no values yet. Throws Error on absurd options.
LightmapBake prepareTexels(const Scene& scene, const LightmapAtlas& atlas, const LightmapBakeOptions& options);

// Lays every plane out on `pageCount` pages (value(plane, element) at each element's texel), then
// fills, stitches and dilates them all alike; the seam statistics are those of plane 0. Sets
// bake.state and adds to bake.secondsPost.
void finishPlanes(const LightmapBakeOptions& options, LightmapBake& bake, int pageCount,
                  const std::vector<std::vector<std::vector<Rgb>>*>& planes,
                  const std::function<Rgb(size_t plane, size_t element)>& value);

}  // namespace luxel::lightmap
