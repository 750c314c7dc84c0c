// The stages of buildLightmapAtlas (lightmap.h), one file each: charts.cpp (segmentation),
// planar.cpp and lscm.cpp (parameterisation), pack.cpp (packing), existing_uvs.cpp (given UVs),
// raster.cpp (texel-centre rasterisation, shared by the checks), chart_neighbours.cpp (texels
// that bilinear filtering mixes across charts, shared with the texel diagnostics).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "luxel/lightmap.h"

namespace luxel::lightmap {

// A mesh with its vertices welded by position: faces sharing an edge share welded indices.
struct WeldedMesh {
  std::vector<Vec3> positions;             // welded
  std::vector<std::array<uint32_t, 4>> v;  // per face, welded corners (triangles repeat corner 2)
  std::vector<int> corners;                // per face, 3 or 4
  std::vector<Vec3> normal;                // per face, unit (zero for degenerate faces)
  std::vector<float> area;                 // per face
};
WeldedMesh weld(const Mesh& mesh);

// A chart: faces of one mesh and, after parameterisation, a UV per face corner (in metres).
struct Chart {
  uint32_t mesh = 0;
  std::vector<uint32_t> faces;
  std::vector<std::array<Vec2, 4>> uv;  // parallel to faces
  bool planar = false;                  // flattened by projection (else LSCM)
};

// Segments a mesh into connected charts of faces whose normals lie within maxAngle (radians) of
// the chart's area-weighted mean normal.
std::vector<Chart> segmentCharts(const WeldedMesh& w, uint32_t meshIndex, float maxAngle);
// Splits a face set into its edge-connected components.
std::vector<std::vector<uint32_t>> connectedComponents(const WeldedMesh& w,
                                                       const std::vector<uint32_t>& faces);

// The area-weighted mean normal of a face set (unit; +z when it cancels out).
Vec3 meanNormal(const WeldedMesh& w, const std::vector<uint32_t>& faces);
// Largest angle (radians) between a face normal and the mean normal.
float maxNormalDeviation(const WeldedMesh& w, const std::vector<uint32_t>& faces, Vec3 mean);
// Projects the chart onto the plane of its mean normal. Returns false when a face flips.
bool planarProject(const WeldedMesh& w, Chart& chart);
// Least squares conformal map (Levy et al. 2002). Returns false when the solve fails or a face
// flips; chart.uv is then unspecified.
bool lscm(const WeldedMesh& w, Chart& chart);
// Parameterises every chart: planar when flat, else LSCM, else planar projection, else splits it
// in two (and again) until every piece flattens without flips. Scales each chart to metres (UV
// area equals surface area).
std::vector<Chart> parameterise(const WeldedMesh& w, std::vector<Chart> charts);

// Signed area of a UV triangle.
inline float signedArea(Vec2 a, Vec2 b, Vec2 c) {
  return 0.5f * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

// Calls f(x, y) for every texel whose centre (x + 0.5, y + 0.5) lies inside the triangle, with a
// top-left rule so that triangles sharing an edge never both claim a texel. Clipped to [0, size).
void rasteriseTriangle(Vec2 a, Vec2 b, Vec2 c, int size,
                       const std::function<void(int, int)>& f);

// Packs charts (UVs in metres) at `density` texels per metre onto pages, writing the texel
// coordinates into atlas.faces and returning the number of pages used (firstPage onwards).
// Charts larger than a page are scaled down to fit it.
struct PackResult {
  int pages = 0;
  size_t scaledDown = 0;  // charts larger than a page, scaled down
};
PackResult packCharts(const std::vector<Chart>& charts, float density, const AtlasOptions& options,
                      uint32_t firstPage, uint32_t firstChart, LightmapAtlas* atlas);
// The number of pages packCharts would use (no output).
int pagesNeeded(const std::vector<Chart>& charts, float density, const AtlasOptions& options);

// Per texel of a page of chart ids (kNoChart where no face claims it): 1 where a texel of another
// chart is among its 8 neighbours, which bilinear filtering at a point of the texel reads, so the
// two charts' light is mixed there and no dilation can undo it (chart_neighbours.cpp).
inline constexpr uint32_t kNoChart = UINT32_MAX;
std::vector<uint8_t> nextToAnotherChart(const std::vector<uint32_t>& chart, int size);

// Given UVs that are no lightmap layout: the faces whose UV area is (near) zero, for their share of
// the mesh's UV area by their surface area, hold more than half the mesh's surface. Such UVs bake
// black (no texel centre falls in a face of no area), so the atlas unwraps the mesh itself with a
// warning. Returns that warning, or "" when the UVs are usable.
std::string degenerateGivenUvs(const Scene& scene, uint32_t meshIndex);

// Checks the lightmapUvs of meshes that share one page (in [0,1], no two faces claiming a texel at
// pageSize unless keepOverlaps) and writes them to atlas.faces[mesh] on `page`, one chart per
// UV-connected component of a mesh, numbered from firstChart; charts with no gutter between them
// add a warning to atlas.warnings. Returns the number of charts. Throws Error naming the mesh or
// meshes.
size_t useExistingUvs(const Scene& scene, std::span<const uint32_t> meshes, int pageSize, uint32_t page,
                      uint32_t firstChart, bool keepOverlaps, LightmapAtlas& atlas);

}  // namespace luxel::lightmap
