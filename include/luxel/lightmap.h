// Lightmap atlases: every mesh's faces laid out in texel space, in charts, on square pages.
//
// A mesh without a second UV set is cut into charts (faces joined by edges whose normals stay
// within chartAngle of the chart's mean normal), each chart is flattened (planar projection when
// flat, least squares conformal maps otherwise) and the charts are packed onto pages with a gutter.
// A mesh with Mesh::lightmapUvs keeps them, after a check. docs/lightmaps.md has the details.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "luxel/directional_lightmap.h"
#include "luxel/image.h"
#include "luxel/progress.h"
#include "luxel/render.h"
#include "luxel/scene.h"
#include "luxel/solve.h"
#include "luxel/surface.h"

namespace luxel {

struct AtlasOptions {
  float texelsPerMetre = 0.0f;  // > 0: this density; 0: the largest density whose charts fit on one page
  int pageSize = 1024;          // texels per side of each square page (16..16384)
  int gutter = 2;               // empty texels kept round every chart (for dilation and bilinear filtering)
  float chartAngle = 45.0f;     // degrees: neighbouring faces whose normals differ more start a new chart
  bool useMeshUvs = true;       // use Mesh::lightmapUvs where a mesh has them (checked)
  // Pages sized to their content: the smallest power of two (16 at least, pageSize at most) at
  // which the generated charts need no more pages than at pageSize, so a small scene does not sit
  // in a corner of a large page. Needs texelsPerMetre > 0 (the fitted density depends on the page);
  // ignored when a mesh brings its own UVs (their resolution is the page's).
  bool sizePagesToContent = false;
  // Given UVs that overlap are kept as they are instead of an error, for diagnostics
  // (luxel/texel_diagnostics.h, luxel view's texels view): a bake of them mixes the faces' light.
  bool keepOverlappingUvs = false;
  // Meshes whose given UVs address one shared page (an engine's lightmap atlas, or the pages of a
  // glb that `luxel bake` wrote): per mesh, the page its UVs are on; meshes with the same number
  // share a page, checked together for overlaps and gutters. Empty, or a negative number: the
  // mesh's UVs fill a page of their own.
  std::vector<int> givenUvPages;
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
  // What the atlas did on its own, for the caller to show: meshes whose given UVs had no area and
  // were unwrapped instead (docs/lightmaps.md, "Given UVs").
  std::vector<std::string> warnings;
};

// Throws Error naming the mesh when given UVs overlap (unless kept) or leave [0,1], or options are
// absurd. Given UVs of (nearly) no area are replaced by luxel's own, with a warning in
// LightmapAtlas::warnings; given charts that touch with no texel between them (bilinear filtering
// will mix their light) are kept with a warning.
LightmapAtlas buildLightmapAtlas(const Scene& scene, const AtlasOptions& options = {});

// ---- Baking: texels as elements (docs/lightmaps.md, "Baking") ----------------------------------

// Every covered texel of an atlas as an element of a SurfaceSet, for the ordinary solvers. Faces
// are the scene's faces, front side only (a two-sided material bakes its front: the side of its
// winding, or the side discretise would turn it to when its back is the lit one). A texel belongs
// to the face whose texel-space triangle holds its centre (top-left rule); faces flagged
// FaceUv::conservative take the free texels they touch. Element: centroid = the world point at the
// texel centre (clamped into the face for conservative faces), polygon = the texel square clipped
// to the face (cut down to 4 corners at face corners), area = the exact world area of that clip.
// Patches: blocks of texelsPerPatchSide^2 texels of one face on one page; the patch polygon is the
// block square clipped to the face, so patches tile every face exactly where it is convex in
// texel space and cut down to 4 corners.
struct TexelSurfaces {
  SurfaceSet surfaces;
  struct Texel {
    uint32_t page = 0;
    uint32_t x = 0, y = 0;  // texel column and row on the page (row 0 at v = 0, the bottom)
  };
  std::vector<Texel> texels;                   // per element of `surfaces`
  std::vector<std::array<Vec2, 4>> faceTexels; // per face of `surfaces`: corners in texel units, same order
  std::vector<uint32_t> faceChart;             // per face of `surfaces`
  std::vector<uint32_t> facePage;              // per face of `surfaces`
  // Texels whose centre a second face also holds (given UVs that overlap; the first face keeps
  // the texel), once per extra claim.
  std::vector<Texel> contested;
  size_t skippedFaces = 0;                     // faces with no area in space or in texel space
};
TexelSurfaces texelSurfaces(const Scene& scene, const LightmapAtlas& atlas, int texelsPerPatchSide = 8,
                            bool orientByLight = true);

struct LightmapBakeOptions {
  SolveOptions solve;             // texels are not split: refine.budget must be 0
  int texelsPerPatchSide = 8;
  // Validity: rays per texel (rounded down to a square) over the hemisphere; a texel whose rays
  // hit more than maxBackfaceShare back faces (of single-sided materials) sees the inside of
  // geometry: its value is discarded and filled from valid texels of its chart.
  int validityRays = 16;
  float maxBackfaceShare = 0.1f;
  // Seams: edges shared in 3D by faces of different charts whose normals differ by less than
  // seamAngle degrees get the texels on both sides averaged.
  bool stitchSeams = true;
  float seamAngle = 45.0f;
  // Dilation passes into the empty texels round every chart (the atlas gutter).
  int dilation = 2;
  // Also keep where each texel's light comes from (luxel/directional_lightmap.h): exactly from
  // each patch's share with CPU progressive and gather, by a final gather of rays with the other
  // solvers (the hierarchy, GL).
  DirectionalMode directional = DirectionalMode::None;
};

struct LightmapBake {
  enum State : uint8_t { Empty = 0, Solved = 1, Filled = 2, Dilated = 3 };
  int pageSize = 0;
  // Irradiance H (W m^-2, all light arriving on the front: direct, interreflected and analytic),
  // per page, [y * pageSize + x], row 0 at v = 0 (the bottom). Outgoing radiance is
  // reflectance * H / pi + emission: three.js's lightMap convention.
  std::vector<std::vector<Rgb>> pages;
  std::vector<std::vector<uint8_t>> state;  // per texel, State
  TexelSurfaces surfaces;
  Solution solution;
  std::vector<uint8_t> valid;  // per element: passed the backface test
  size_t texels = 0;           // covered texels (elements)
  size_t invalidTexels = 0;    // failed the backface test (then filled)
  size_t unfilledTexels = 0;   // invalid with no valid texel in their chart (left at their solved value)
  size_t dilatedTexels = 0;
  size_t seamEdges = 0, seamSamples = 0;
  float seamMaxBefore = 0.0f;  // largest relative difference (|a-b| summed over channels / mean) across seams
  float seamMaxAfter = 0.0f;
  double secondsSurfaces = 0, secondsValidity = 0, secondsSolve = 0, secondsPost = 0;
  double secondsSeams = 0;     // the part of secondsPost spent finding and stitching seams
  double secondsDirectional = 0;  // the directions of the light, after the solve
  // How the interreflected light's directions were found: "solver" (each patch's shot along its
  // exact directions, Solver::incidentSh) or "gathered" (rays from every texel, for solvers that
  // keep no record); empty for DirectionalMode::None.
  std::string directionsFrom;
  // Directional bakes: the incident radiance's SH, directionalCoefficients(directional) planes
  // laid out as `pages` ([coefficient][page][texel]), filled, stitched and dilated as the pages
  // are (and windowed for ShL2); empty for DirectionalMode::None.
  DirectionalMode directional = DirectionalMode::None;
  std::vector<std::vector<std::vector<Rgb>>> sh;
};

LightmapBake bakeLightmaps(const Scene& scene, const LightmapAtlas& atlas, const LightmapBakeOptions& options = {},
                           const ProgressCallback& progress = {});

// The recipe `luxel render --mode lightmap` and `luxel bake --lightmaps` share: an atlas, then a
// bake whose dilation fills the atlas's gutter. The density, in this order: texelsPerMetre when
// > 0; about texelBudget texels when > 0 (every texel is an element of the solve); otherwise
// defaultTexelsPerMetre(scene). Pages: pageSize when > 0, else sized to their content up to
// kMaxDefaultPageSize (AtlasOptions::sizePagesToContent), as many as the charts need.
struct LightmapRecipe {
  float texelsPerMetre = 0.0f;
  size_t texelBudget = 0;
  int pageSize = 0;
  std::vector<int> givenUvPages;  // AtlasOptions::givenUvPages: meshes whose given UVs share pages
  SolveOptions solve;
  DirectionalMode directional = DirectionalMode::None;  // LightmapBakeOptions::directional
};
constexpr int kMaxDefaultPageSize = 1024;
// Most texels a recipe may ask for (every texel is an element of the solve, ~300 bytes with its
// solution): a hundred million is ~30 GB. The recipe checks the density against the scene's area
// before building anything.
constexpr double kMaxLightmapTexels = 1e8;
// A game's density: Godot's default lightmap texel is 0.2 m (LightmapGI texel_scale 1), 5 texels
// per metre, what it ships for a level. Luxel solves every texel as an element, so denser (Unity's
// default 40 texels per unit, for its path tracer) costs 64x the texels of a solve.
constexpr float kGameTexelsPerMetre = 5.0f;
// Small scenes get more: the density of about this many texels, a short solve.
constexpr size_t kSmallSceneTexels = 10000;
// The default density makes at most this many texels (~0.6 GB to solve). Faces over 80,000 m^2
// at 5 per metre are a vast level or, more often, a file not in metres (the conference room's
// OBJ, in units of 3 mm, claims 2.4e7 m^2); a default must not fail or take an hour.
constexpr double kDefaultMaxTexels = 2e6;
// max(kGameTexelsPerMetre, the density of kSmallSceneTexels texels over the scene's faces), but
// no more than the density of kDefaultMaxTexels texels.
float defaultTexelsPerMetre(const Scene& scene);
// Why the default density is lower than a game's for this scene, naming its area and what to do
// (scale the file to metres, or give a density); empty when it is not.
std::string defaultDensityWarning(const Scene& scene);
struct BakedLightmaps {
  LightmapAtlas atlas;
  LightmapBake bake;
};
BakedLightmaps bakeLightmaps(const Scene& scene, const LightmapRecipe& recipe, const ProgressCallback& progress = {});
// The atlas options the recipe chooses for `scene` (density and pages); throws Error on a negative
// or non-finite density or page size, and on a density that would give more than
// kMaxLightmapTexels texels over the scene's faces.
AtlasOptions lightmapAtlasOptions(const Scene& scene, const LightmapRecipe& recipe);

// A page as an image, row 0 at the top (v = 1), for writeExr.
Image lightmapPageImage(const LightmapBake& bake, int page);
// RGBM, 8 bits per channel, linear (no sRGB curve): value = rgb/255 * alpha/255 * range, with
// range the smallest power of two at or above the page's largest component (at least 1).
float rgbmRange(const Image& image);
std::vector<uint8_t> encodeRgbmPng(const Image& image, float range);
// Direction texture `texture` of a directional bake's page as an 8-bit RGB PNG, row 0 at the top
// (the encoding of luxel/directional_lightmap.h).
std::vector<uint8_t> encodeDirectionalPng(const LightmapBake& bake, int page, int texture);

// The density that gives about `texels` texels over the scene's faces (0 for an empty scene).
float texelsPerMetreForBudget(const Scene& scene, size_t texels);
// The area of the scene's faces (one side), in square scene units.
double sceneFaceArea(const Scene& scene);

// Renders the scene as a real-time engine shows the bake: primary rays against the scene's faces,
// L = Le + rho / pi * H with H sampled bilinearly from the lightmap pages (src/render/lightmap_renderer.cpp);
// a directional bake on a normal-mapped material reads H at the normal map's normal
// (directionalIrradiance, luxel/directional_lightmap.h).
Image renderLightmapped(const Scene& scene, const LightmapAtlas& atlas, const LightmapBake& bake,
                        const RenderOptions& options, const ProgressCallback& progress = {},
                        RenderStats* stats = nullptr);

}  // namespace luxel
