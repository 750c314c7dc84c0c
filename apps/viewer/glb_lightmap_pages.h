// Which lightmap page of a baked glb each mesh of the scene imported from it lies on, so that the
// texels view and a new bake lay a glb's own lightmap UVs out as the glb does: meshes that share a
// page image checked together, at the image's size (luxel/lightmap.h, AtlasOptions::givenUvPages).
#pragma once

#include <string>
#include <vector>

#include "baked_glb.h"
#include "luxel/scene.h"

namespace luxel::viewer {

struct GlbLightmapPages {
  std::vector<int> meshPage;  // per scene mesh: the lightmap image its UVs address, or -1
  int pageSize = 0;           // the images' side in texels; 0 when the pages cannot be kept
  size_t meshesWithUvs = 0;   // scene meshes that have lightmap UVs
  size_t matched = 0;         // of those, the ones matched to a lightmapped primitive
  // Why the pages cannot be kept (pageSize 0), for a message; empty when they can.
  std::string whyNot;
};

// Assimp makes a mesh of each glb primitive (`luxel bake` writes one per mesh and page), in an
// order and with a vertex welding of its own, so meshes are matched to primitives by what survives
// both: their triangles' world-space bounds and area, and their lightmap UVs' bounds.
GlbLightmapPages glbLightmapPages(const BakedGlb& glb, const Scene& scene);

}  // namespace luxel::viewer
