// Images from a solution: primary rays through a pinhole camera, radiance = B / pi interpolated
// smoothly over elements, and optionally exact direct light per pixel.
#pragma once

#include <cstdint>

#include "luxel/image.h"
#include "luxel/progress.h"
#include "luxel/solve.h"

namespace luxel {

// The vertex gather's mesh by default (RenderOptions::gatherElements), and the element budget the
// command line gives an hq render's solve when none is asked for: the image is gathered on about
// 10,000 elements while the solve runs on a quarter of them, and reading that solution three
// bounces away costs it no accuracy measured against a path tracer (docs/performance.md).
inline constexpr size_t kDefaultGatherElements = 10000;
inline constexpr size_t kHqSolveElements = 2500;

inline constexpr int kDefaultGlossyRays = 4;

struct RenderOptions {
  enum class Mode {
    // The seeds' display: all light, direct included, interpolated from the element solution.
    // Normal maps are ignored.
    Radiosity,
    // Direct light evaluated per pixel with shadow rays towards stratified points of each light
    // (exact shadows, smooth penumbrae), and the indirect light found as `indirect` says. The
    // receiver cosine of the direct light (and of a per-pixel gather) is taken at the material's
    // normal map (Material::normalTexture) where there is one.
    HighQuality,
  };
  // Where HighQuality finds the indirect light (render/final_gather.h).
  enum class Indirect {
    // VertexGather up to kMaxAutoGatherElements solved elements, Interpolated above. Against
    // path-traced probes the gathered irradiance is nearer on every scene measured; past a few
    // million elements the gather's state (hundreds of bytes an element over three gathered
    // bounces) and time cost more than a render of that size can spend (docs/performance.md,
    // "What the gather shows").
    Auto,
    // The element solution's indirect irradiance, interpolated: the fastest, but the
    // discretisation shows (patches shooting their mean, elements averaged across contacts).
    Interpolated,
    // A final gather at the element vertices (of the solved elements, or those split further:
    // gatherElements), interpolated per pixel: rays read the solution gatherBounces bounces away,
    // with the direct light traced where they land, or read from the solution where they land a
    // few elements away. Smooth, and cheap at any image size.
    VertexGather,
    // A final gather at every pixel sample: no interpolation at all, so contact shadows and
    // normal maps reach the indirect light too, at the price of noise.
    PixelGather,
    // No indirect light: the direct light alone, to check it apart (against a path tracer's
    // render of one bounce, say).
    None,
  };
  Mode mode = Mode::HighQuality;
  Camera camera;
  int width = 512;
  int height = 512;
  // Light points per pixel (a shadow ray per light each), and as many camera samples (pixel
  // jitter), except inside faces: a pixel whose corners all see one untextured face takes a quarter
  // of the camera samples, each with four of the light points, when the count is a multiple of 4
  // and no light casts hard shadows (point, spot, sun); docs/algorithms.md, "Rendering".
  int samplesPerPixel = 16;
  Indirect indirect = Indirect::Auto;
  // Gather rays per vertex (VertexGather) or per pixel sample (PixelGather); 0 takes the mode's
  // default: kDefaultPixelGatherRays, or kDefaultVertexGatherRays where the scene's vertices allow
  // (render/final_gather.h keeps the whole gather to about 16 million rays).
  int gatherRays = 0;
  // Bounces gathered before the solution is read: 1, at the gather's hits; 2, where the hits read
  // a coarse gather of every vertex (kCoarseGatherRays each), which halves what is left of the
  // solution's error in no more time than the one-bounce gather's near hits cost; 3 (default) or
  // 4, where that coarse gather reads another in turn, so that a solve on coarse patches (the
  // solve kHqSolveElements makes) is met further away, for 16 rays a vertex a level
  // (docs/performance.md, "Against a peer").
  int gatherBounces = 3;
  // VertexGather's mesh: the solved elements split (each into 4, as often as it takes) until they
  // are nearest this many, so that the solve can run on fewer elements than the picture
  // interpolates over (render/gather_mesh.h). 0, or no more than the solved elements: as solved.
  size_t gatherElements = kDefaultGatherElements;
  // hq mode, on glossy materials (Material::specular, shininess): rays per camera sample drawn
  // from the highlight's lobe (render/glossy_lobe.h), which read the light of emitting surfaces,
  // skies and lit surfaces where they land; lamps, spots and suns add theirs by a shadow ray each.
  // 0 draws no highlights (the picture then is the diffuse solution's alone).
  int glossyRays = kDefaultGlossyRays;
  uint32_t seed = 7;
};

inline constexpr int kDefaultVertexGatherRays = 256;
inline constexpr int kDefaultPixelGatherRays = 4;
inline constexpr int kCoarseGatherRays = 16;

inline constexpr int kMaxImageSide = 32768;
// 16384 x 16384: the float image alone is 3 GiB, and a bigger poster is rendered in tiles.
inline constexpr uint64_t kMaxImagePixels = uint64_t(16384) * 16384;

// Throws Error when the options are absurd: a side outside [1, kMaxImageSide], more than
// kMaxImagePixels pixels, samples outside [1, 65536], gather or glossy rays outside [0, 65536] (or,
// per pixel sample, their product with the samples over 2^20), gather bounces other than 1 or 2, a field of
// view outside (0, 180) degrees, a camera whose eye, target and up do not span a frame or lie
// beyond kMaxCoordinate. render() calls it; a caller can call it before the solve, to fail early.
void validateRenderOptions(const RenderOptions& options);

struct RenderStats {
  double seconds = 0.0;
  uint64_t rays = 0;  // primary, shadow and gather rays
  RenderOptions::Indirect indirect = RenderOptions::Indirect::Interpolated;  // what Auto chose
  size_t gatherElements = 0;  // the elements a vertex gather ran on (0: no vertex gather)
};

// The most solved elements Indirect::Auto gathers at vertices over.
inline constexpr size_t kMaxAutoGatherElements = size_t(1) << 22;
// The indirect light `options` asks for, with Auto resolved for `surfaces`.
RenderOptions::Indirect resolvedIndirect(const RenderOptions& options, const SurfaceSet& surfaces);
// "auto", "interpolated", "vertex-gather", "pixel-gather".
const char* indirectName(RenderOptions::Indirect indirect);

// Renders `solution` of `surfaces` (discretised from `scene`). Throws Error on absurd options
// (validateRenderOptions) and Cancelled on request.
Image render(const Scene& scene, const SurfaceSet& surfaces, const Solution& solution,
             const RenderOptions& options, const ProgressCallback& progress = {},
             RenderStats* stats = nullptr);

RenderOptions::Mode parseRenderMode(const std::string& name);  // "radiosity" | "hq"
// "auto" | "interpolated" | "vertex-gather" | "pixel-gather" | "none"
RenderOptions::Indirect parseIndirect(const std::string& name);

// The per-vertex (element corner) values of a per-element quantity, averaged over the elements
// that meet there on the same smooth surface (same material, normals within 30 degrees).
// Returns 4 values per element (triangles leave the 4th unused).
std::vector<Rgb> elementCornerValues(const SurfaceSet& surfaces, const std::vector<Rgb>& perElement);

}  // namespace luxel
