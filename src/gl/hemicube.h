// Hemicubes (Cohen and Greenberg, "The Hemi-Cube: A Radiosity Solution for Complex Environments",
// SIGGRAPH 1985), as seeds 000 and 001 render them: five rasterised faces around a receiver point,
// each pixel weighted by its delta form factor.
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "luxel/surface.h"

namespace luxel::gl {

// Delta form factors of a hemicube of half-width 1 whose top face has `resolution` pixels a side
// (Cohen and Greenberg 1985): top pixel at (x, y, 1): dA / (pi (x^2 + y^2 + 1)^2); side pixel at
// height z: z dA / (pi (x^2 + z^2 + 1)^2). The discrete sum misses 1 by the midpoint rule's error
// (+0.86% at 8 pixels, +0.21% at 16, +0.013% at 64); the tables are scaled so that it is 1
// exactly, which seed 000's multiplier maps were not (its notes, point 5).
struct DeltaFormFactors {
  int resolution = 0;
  std::vector<float> top;   // resolution x resolution, row-major
  std::vector<float> side;  // resolution x resolution/2: the upper half of a side face, row 0 at the base
  double rawSum = 0.0;      // the sum before scaling

  explicit DeltaFormFactors(int resolution);
};

// How a rendered hemicube becomes per-item form factors.
enum class HemicubeIntegration {
  // A compute pass reads the five-layer item texture and adds each pixel's delta form factor to
  // its item's sum with integer atomics on fixed point (shared_layout.h: one unit is 2^-31); only
  // the per-item sums come back. The default.
  Compute,
  // glReadPixels of each face and a sum on the CPU: the reference the compute pass is tested on.
  ReadBack,
};

struct HemicubeOptions {
  int resolution = 64;     // top-face pixels per side (001: 64)
  float nearPlane = 1e-4f; // relative to the scene extent: geometry closer than this is clipped
  HemicubeIntegration integration = HemicubeIntegration::Compute;
};

// Renders item-buffer hemicubes of a fixed set of polygons (uploaded once) and returns, per
// polygon, the form factor from a receiver point to what of it is visible.
class ItemHemicube {
 public:
  // Needs a current OpenGL 4.5 context (gl::Context). `sceneExtent` sets near and far planes.
  ItemHemicube(std::span<const Polygon> polygons, float sceneExtent, const HemicubeOptions& options = {});
  ~ItemHemicube();

  // F from a differential area at `p` with unit normal `n` to each polygon, occlusion included.
  std::vector<float> formFactors(Vec3 p, Vec3 n);
  // The same into `out` (one float per polygon), which is overwritten.
  void formFactors(Vec3 p, Vec3 n, std::span<float> out);

  HemicubeIntegration integration() const { return integration_; }

  const DeltaFormFactors& deltas() const { return deltas_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  DeltaFormFactors deltas_;
  size_t polygonCount_ = 0;
  HemicubeIntegration integration_ = HemicubeIntegration::Compute;

  void render(Vec3 p, Vec3 n, std::span<float> out);
};

}  // namespace luxel::gl
