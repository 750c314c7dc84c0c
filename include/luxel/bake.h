// Baking a solution into the scene's own meshes and writing them out as glTF 2.0 binary (.glb),
// for display in real-time viewers (docs/baking.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "luxel/directional_lightmap.h"
#include "luxel/lightmap.h"
#include "luxel/scene.h"
#include "luxel/solve.h"
#include "luxel/surface.h"

namespace luxel {

// Per face corner of the scene's meshes: [mesh][face * 4 + corner] (a triangle leaves its 4th
// entry unused). The layout `GlbOptions` takes for vertex attributes.
using FaceCornerValues = std::vector<std::vector<Rgb>>;

// The value of a per-element quantity at every face corner of every mesh: the smooth per-vertex
// value of elementCornerValues (render.h) at the element corner that coincides with the face
// corner, on the face's front side (the side the solver lit: a face that discretisation turned
// round takes its turned side; a two-sided face its front, the side of its winding). Faces that
// discretisation dropped as degenerate take the value other faces of the mesh have at the same
// vertex (black when none has one).
FaceCornerValues faceCornerValues(const Scene& scene, const SurfaceSet& surfaces,
                                  const std::vector<Rgb>& perElement);

// Outgoing radiance B / pi at every face corner (emission included): the colour a camera sees.
FaceCornerValues bakedRadiance(const Scene& scene, const SurfaceSet& surfaces, const Solution& solution);
// The same at every element corner (elementCornerValues' layout, 4 per element).
std::vector<Rgb> elementRadiance(const SurfaceSet& surfaces, const Solution& solution);

// Directions per vertex (issue 17): the values of the direction textures of a directional
// lightmap (directional_lightmap.h's encoding, before 8-bit quantising) at every element corner:
// directionalTextureCount(mode) lists, 4 per element in elementCornerValues' layout. `sh` holds
// directionalCoefficients(mode) coefficients per element (Session::incidentSh); each coefficient is
// carried to the corners as the colours are (elementCornerValues), and L2 windowed at each corner
// so that no normal reads negative light. Throws Error when the sizes do not match.
std::vector<std::vector<Rgb>> elementDirections(const SurfaceSet& surfaces, DirectionalMode mode,
                                                const std::vector<Rgb>& sh);

// An image embedded in the glb as PNG (e.g. a lightmap page): encoded bytes.
struct GlbImage {
  std::string name;
  std::vector<uint8_t> png;
  // > 0: a lightmap page in RGBM (value = rgb * alpha * rgbmRange, linear), sampled with
  // clamp-to-edge and no mipmaps.
  float rgbmRange = 0.0f;
  // Data sampled like a lightmap page (clamp-to-edge, no mipmaps), not a colour: the direction
  // textures of a directional bake.
  bool clamped = false;
};

struct GlbOptions {
  // COLOR_0, float VEC3, linear, per vertex: empty for none, else FaceCornerValues layout, where
  // a mesh's own list may be empty (no COLOR_0 on that mesh); finite and >= 0. glTF wants colours
  // in [0,1]: they are written divided by S, the smallest power of two at or above the largest
  // component (1 when that is <= 1), and S is recorded in the scene's extras as
  // {"luxel": {"vertexColors": vertexColorQuantity, "vertexColorScale": S}}.
  FaceCornerValues vertexColors;
  std::string vertexColorQuantity = "radiance";
  // Vertex colours on the element tessellation, for meshes too coarse to carry the lighting at
  // their own vertices (a floor that is one quad): when `elements` is set, every mesh is written
  // as the elements cut from its faces (their front sides; faces dropped as degenerate are left
  // out), and COLOR_0 holds `elementColors`, 4 per element in elementCornerValues' layout (render.h),
  // scaled as above. Excludes vertexColors and secondUvs.
  const SurfaceSet* elements = nullptr;
  std::vector<Rgb> elementColors;
  // Directions per vertex for `vertexDirectionalMode` ("" for none), written as float VEC3
  // attributes _LUXEL_DIRECTION0, 1, ... that each primitive's LUXEL_vertex_directional extension
  // names (docs/baking.md, docs/schema/LUXEL_vertex_directional.schema.json), in extensionsUsed,
  // not required: with `elements`, elementDirections' lists; with vertexColors,
  // lightmapCornerDirections' lists (FaceCornerValues layout, on the meshes that have colours).
  std::string vertexDirectionalMode;
  std::vector<std::vector<Rgb>> elementDirections;
  std::vector<FaceCornerValues> vertexDirections;
  // TEXCOORD_1 (the lightmap UV set): empty for none, else per mesh, per face corner
  // ([mesh][face * 4 + corner]; empty for a mesh without), v up as in Mesh::uvs (written
  // flipped, as glTF wants).
  std::vector<std::vector<Vec2>> secondUvs;
  // Extra images, embedded with a texture each (after the material textures), in this order.
  std::vector<GlbImage> images;
  // Lightmaps: per mesh, per face, the index into `images` of its lightmap page (-1 for none), or
  // empty (for all meshes, or for one mesh: no lightmap on it). Faces are grouped into one
  // primitive per page, with a copy of their material per page whose extras say {"luxel":
  // {"lightMap": TEXTURE, "lightMapTexCoord": 1, "lightMapEncoding": "RGBM", "rgbmRange": R,
  // "lightMapQuantity": "irradiance"}} (docs/baking.md). Needs the mesh's secondUvs.
  std::vector<std::vector<int32_t>> faceLightmap;
  // Directional lightmaps (luxel/directional_lightmap.h): the mode's name ("" for none) and, per
  // image of `images` that is a lightmap page, the indices into `images` of its direction
  // textures in the order of the mode's encoding (empty for images that are not pages). Each
  // lightmapped material copy then carries them in the LUXEL_lightmap_directional extension
  // (docs/baking.md, docs/schema/LUXEL_lightmap_directional.schema.json), listed in extensionsUsed
  // and not required: an engine that ignores it still has the plain lightmap.
  std::string directionalMode;
  std::vector<std::vector<int32_t>> directionalImages;
  // SH transfer lightmaps (luxel/transfer_lightmap.h), as the LUXEL_lightmap_transfer extension on
  // each lightmapped material copy (docs/baking.md, "Transfer lightmaps in the glb"): bands 0 for
  // none; per image of `images` that is a lightmap page, the indices into `images` of its band-0
  // page (RGBM) and then its ratio textures (empty for other images); and the distant light the
  // fallback lightmap was relit with, sky and suns apart so that a viewer can turn the suns.
  int transferBands = 0;
  std::vector<std::vector<int32_t>> transferImages;
  // Per image as transferImages: the scale of each coefficient i >= 1's ratio on that page (the
  // largest |T_i / T_0| there), so that 8 bits cover what the page holds.
  std::vector<std::vector<float>> transferRatioScales;
  std::vector<Rgb> transferSky;  // transferBands^2 coefficients
  struct Sun {
    Vec3 direction{0.0f};  // the way its light travels
    Rgb irradiance{0.0f};
  };
  std::vector<Sun> transferSuns;
  // Faces that discretisation turned round (SurfaceFace::flipped) are written turned round too,
  // so that viewers culling back faces show the side the solver lit: one flag per mesh face,
  // [mesh][face], empty for none. bakeGlbOptions fills it.
  std::vector<std::vector<uint8_t>> flippedFaces;
  std::string generator = "luxel";
};

// The flipped-face flags of `surfaces` in GlbOptions::flippedFaces layout.
std::vector<std::vector<uint8_t>> flippedFaceFlags(const Scene& scene, const SurfaceSet& surfaces);

// The irradiance H of a lightmap bake at every face corner of the meshes flagged in `meshes`
// ([mesh], 1 = wanted; others get an empty list): the baked texels (filled, stitched) of the
// face's own chart around the corner, bilinearly as a renderer samples the lightmap (the nearest
// of them where none of the four is the chart's), averaged over the corners of the mesh at the
// same position whose faces' normals differ by less than 45 degrees (one smooth surface: one
// colour per vertex).
// Corners of faces the bake skipped (no area) take that average too, or 0 without one.
FaceCornerValues lightmapCornerIrradiance(const Scene& scene, const LightmapAtlas& atlas, const LightmapBake& bake,
                                          const std::vector<uint8_t>& meshes);
// A directional bake's direction textures at the same corners: each SH plane read at the texels
// lightmapCornerIrradiance reads and averaged as it averages, then encoded as the textures are
// (encodeDirectionalTexel, before 8-bit quantising): directionalTextureCount(bake.directional)
// lists. Throws Error for a bake without directions.
std::vector<FaceCornerValues> lightmapCornerDirections(const Scene& scene, const LightmapAtlas& atlas,
                                                       const LightmapBake& bake, const std::vector<uint8_t>& meshes);

// Adds a lightmap bake to `o`: TEXCOORD_1 from the atlas (texel / page size), the pages the
// lightmapped faces use as RGBM PNG images (appended to o.images, named lightmapN after the page)
// and the faces' images (o.faceLightmap). Meshes flagged in `vertexColorMeshes` ([mesh], 1 =
// flagged; empty for none) get no TEXCOORD_1 and no lightmap but COLOR_0 =
// lightmapCornerIrradiance, with vertexColorQuantity "irradiance" (docs/baking.md). A directional
// bake adds each page's direction textures (8-bit PNG, directional_lightmap.h's encoding), and
// the vertex-coloured meshes' directions (lightmapCornerDirections).
void addLightmaps(GlbOptions& o, const Scene& scene, const LightmapAtlas& atlas, const LightmapBake& bake,
                  const std::vector<uint8_t>& vertexColorMeshes = {});

// Writes `scene` as a glTF 2.0 binary: one glTF mesh and node per luxel mesh (triangles, quads
// split along their 0-2 diagonal, flat normals, TEXCOORD_0 when the mesh has uvs), one
// metallic-roughness material per luxel material (base colour = reflectance and its texture,
// emissive = emission, with KHR_materials_emissive_strength above 1; metallic 0, roughness 1,
// doubleSided = twoSided), the cameras, and what `options` adds. Writes atomically; throws Error
// naming the path on failure or when the options do not match the scene.
void writeGlb(const Scene& scene, const std::filesystem::path& path, const GlbOptions& options = {});

}  // namespace luxel
