// Images from a solution: primary rays through a pinhole camera, radiance = B / pi interpolated
// smoothly over elements, and optionally exact direct light per pixel.
#pragma once

#include <cstdint>

#include "luxel/image.h"
#include "luxel/progress.h"
#include "luxel/solve.h"

namespace luxel {

struct RenderOptions {
  enum class Mode {
    // The seeds' display: all light, direct included, interpolated from the element solution.
    // Normal maps are ignored.
    Radiosity,
    // Direct light evaluated per pixel with shadow rays (exact shadows); only the indirect part
    // comes from the element solution. The direct light's receiver cosine uses the material's
    // normal map (Material::normalTexture) where there is one; the indirect part does not.
    HighQuality,
  };
  Mode mode = Mode::HighQuality;
  Camera camera;
  int width = 512;
  int height = 512;
  int samplesPerPixel = 16;  // pixel jitter, and one shadow ray per light per sample
  uint32_t seed = 7;
};

inline constexpr int kMaxImageSide = 32768;
// 16384 x 16384: the float image alone is 3 GiB, and a bigger poster is rendered in tiles.
inline constexpr uint64_t kMaxImagePixels = uint64_t(16384) * 16384;

// Throws Error when the options are absurd: a side outside [1, kMaxImageSide], more than
// kMaxImagePixels pixels, samples outside [1, 65536], a field of view outside (0, 180) degrees, a
// camera whose eye, target and up do not span a frame or lie beyond kMaxCoordinate. render() calls
// it; a caller can call it before the solve, to fail early.
void validateRenderOptions(const RenderOptions& options);

struct RenderStats {
  double seconds = 0.0;
  uint64_t rays = 0;  // primary and shadow rays
};

// Renders `solution` of `surfaces` (discretised from `scene`). Throws Error on absurd options
// (validateRenderOptions) and Cancelled on request.
Image render(const Scene& scene, const SurfaceSet& surfaces, const Solution& solution,
             const RenderOptions& options, const ProgressCallback& progress = {},
             RenderStats* stats = nullptr);

RenderOptions::Mode parseRenderMode(const std::string& name);  // "radiosity" | "hq"

// The per-vertex (element corner) values of a per-element quantity, averaged over the elements
// that meet there on the same smooth surface (same material, normals within 30 degrees).
// Returns 4 values per element (triangles leave the 4th unused).
std::vector<Rgb> elementCornerValues(const SurfaceSet& surfaces, const std::vector<Rgb>& perElement);

}  // namespace luxel
