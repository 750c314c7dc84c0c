// Which lightmap page of a baked glb each mesh of the scene imported from it lies on, so that the
// texels view lays a glb's own lightmap UVs out as the glb does: meshes that share a page image
// checked together, at the image's size (luxel/lightmap.h, AtlasOptions::givenUvPages).
#pragma once

#include <vector>

#include "baked_glb.h"
#include "luxel/scene.h"

namespace luxel::viewer {

struct GlbLightmapPages {
  std::vector<int> meshPage;  // per scene mesh: the lightmap image its UVs address, or -1
  int pageSize = 0;           // the images' side in texels; 0 when there are none or they differ
};

// Assimp makes a mesh of each glb primitive (`luxel bake` writes one per mesh and page), in an
// order and with a vertex welding of its own, so meshes are matched to primitives by what survives
// both: their triangles' world-space bounds and area.
GlbLightmapPages glbLightmapPages(const BakedGlb& glb, const Scene& scene);

}  // namespace luxel::viewer
