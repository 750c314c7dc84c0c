// Lightmap atlases: every mesh's faces laid out in texel space, in charts, on square pages.
//
// A mesh without a second UV set is cut into charts (faces joined by edges whose normals stay
// within chartAngle of the chart's mean normal), each chart is flattened (planar projection when
// flat, least squares conformal maps otherwise) and the charts are packed onto pages with a gutter.
// A mesh with Mesh::lightmapUvs keeps them, after a check. docs/lightmaps.md has the details.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "luxel/scene.h"

namespace luxel {

struct AtlasOptions {
  float texelsPerMetre = 0.0f;  // > 0: this density; 0: the largest density whose charts fit on one page
  int pageSize = 1024;          // texels per side of each square page (16..16384)
  int gutter = 2;               // empty texels kept round every chart (for dilation and bilinear filtering)
  float chartAngle = 45.0f;     // degrees: neighbouring faces whose normals differ more start a new chart
  bool useMeshUvs = true;       // use Mesh::lightmapUvs where a mesh has them (checked)
};

struct LightmapAtlas {
  int pageSize = 0;
  int pageCount = 0;
  float texelsPerMetre = 0.0f;  // of the generated charts (charts larger than a page are scaled down)
  size_t chartCount = 0;
  struct FaceUv {
    uint32_t page = 0;
    uint32_t chart = 0;
    std::array<Vec2, 4> texel{};  // each corner in texel units on its page (0..pageSize); triangles repeat corner 2
    // The face contains no texel centre (it is smaller than a texel, or a sliver): a baker must
    // rasterise it conservatively (every texel it touches). Those texels belong to its chart
    // alone: charts are packed on whole texels with the gutter between them.
    bool conservative = false;
  };
  std::vector<std::vector<FaceUv>> faces;  // [mesh][face], parallel to Scene::meshes[m].faces
};

// Throws Error naming the mesh when given UVs overlap or leave [0,1], or options are absurd.
LightmapAtlas buildLightmapAtlas(const Scene& scene, const AtlasOptions& options = {});

}  // namespace luxel
