// An independent reference for a radiosity solution: the mean irradiance over chosen elements,
// estimated by path tracing (Kajiya, "The Rendering Equation", SIGGRAPH 1986) with next-event
// estimation of every emitter and analytic light (render/direct_light.h) and Russian roulette.
//
// It solves the same continuous problem the solvers discretise (Lambertian surfaces with each
// element's own reflectance, emission as the elements carry it, the scene's analytic lights) but
// shares none of their approximations: no patches, no form factors, no element averaging of the
// light that arrives, no clusters. Each path starts at a point drawn uniformly over the element,
// so the estimate is the element's mean irradiance, the quantity a constant-basis solver's
// Solution::irradiance approximates. Its only error is noise, which it measures and reports.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "luxel/scene.h"
#include "luxel/surface.h"
#include "luxel/progress.h"

namespace luxel {

struct PathTracingOptions {
  // Paths per element: at least minPaths, then batches until the standard error of the mean is
  // at most relativeError of the mean (summed over channels), or maxPaths.
  uint32_t minPaths = 4096;
  uint32_t maxPaths = 1u << 18;
  double relativeError = 0.005;
  uint32_t seed = 0x7a7a7a7au;
  // Bounces a path may take; 0 estimates the direct light alone (Solution::directIrradiance).
  int maxBounces = 1000;
};

struct ElementIrradianceEstimate {
  Rgb mean{0.0f};           // W/m^2, the element's mean irradiance (front side)
  Rgb standardError{0.0f};  // of the mean, per channel
  uint32_t paths = 0;
};

// Estimates the mean irradiance of each of `elements`. Paths end at a surface's back (one-sided
// receivers absorb what arrives behind them, as the solvers do) and when they leave the scene
// (the skies are sampled as lights). Throws Error for two-sided faces, whose coincident sides a
// ray cannot tell apart, and for out-of-range element indices. Parallel over the elements;
// the result depends only on the options' seed, not on the thread count.
std::vector<ElementIrradianceEstimate> pathTraceElementIrradiance(const Scene& scene, const SurfaceSet& surfaces,
                                                                  std::span<const uint32_t> elements,
                                                                  const PathTracingOptions& options,
                                                                  const ProgressCallback& progress = {});

}  // namespace luxel
