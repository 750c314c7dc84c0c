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
    Radiosity,
    // Direct light evaluated per pixel with shadow rays (exact shadows); only the indirect part
    // comes from the element solution.
    HighQuality,
  };
  Mode mode = Mode::HighQuality;
  Camera camera;
  int width = 512;
  int height = 512;
  int samplesPerPixel = 16;  // pixel jitter, and one shadow ray per light per sample
  uint32_t seed = 7;
};

struct RenderStats {
  double seconds = 0.0;
  uint64_t rays = 0;  // primary and shadow rays
};

// Renders `solution` of `surfaces` (discretised from `scene`). Throws Error on absurd options
// (non-positive or over 32768 pixels a side, zero samples) and Cancelled on request.
Image render(const Scene& scene, const SurfaceSet& surfaces, const Solution& solution,
             const RenderOptions& options, const ProgressCallback& progress = {},
             RenderStats* stats = nullptr);

RenderOptions::Mode parseRenderMode(const std::string& name);  // "radiosity" | "hq"

// The per-vertex (element corner) values of a per-element quantity, averaged over the elements
// that meet there on the same smooth surface (same material, normals within 30 degrees).
// Returns 4 values per element (triangles leave the 4th unused).
std::vector<Rgb> elementCornerValues(const SurfaceSet& surfaces, const std::vector<Rgb>& perElement);

}  // namespace luxel
