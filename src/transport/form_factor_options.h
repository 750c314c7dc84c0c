// The CPU transport's settings, and their declarations as solver options: a solver that runs on
// the CPU transport declares them (cpuTransportOptions) and so accepts them from the command line;
// a GPU solver, which takes only the analytic lights from it, declares analyticLightOptions.
#pragma once

#include <cstdint>
#include <vector>

#include "luxel/solver.h"
#include "solve/solver_options.h"

namespace luxel {

struct FormFactorOptions {
  // Visibility rays per element-patch pair; rounded down to a square (1, 4, 9, 16, ...).
  int raysPerPair = 4;
  // Rays for pairs closer than `nearFactor` times their summed sizes, where both the unoccluded
  // form factor and the visibility vary most over the receiver (contacts, corners).
  int nearRaysPerPair = 16;
  // Rays for pairs whose source patch emits: direct light makes the sharpest shadows, and their
  // noise was the largest share of the error against a converged reference (docs/performance.md).
  // Shaft culling leaves only penumbra pairs.
  int emitterRaysPerPair = 64;
  float nearFactor = 2.0f;
  // Classify each receiver-patch/source-patch pair first by shaft culling (Haines and Wallace
  // 1991): when no other face reaches into the hull of the two patches, every element of the
  // pair is wholly visible and casts no rays. Exact; off only to measure what it saves.
  bool classifyVisibility = true;
  // Shadow rays per element for each analytic light (point, spot, sun, sky).
  int lightSamples = 16;
  uint32_t seed = 1;
};

// rays-per-pair, near-rays-per-pair, emitter-rays-per-pair, near-factor, classify-visibility,
// and the analytic-light options.
std::vector<SolverOption> cpuTransportOptions();
// light-samples, seed.
std::vector<SolverOption> analyticLightOptions();

// The options `values` declares, over the defaults for the rest.
FormFactorOptions formFactorOptions(const SolverOptionValues& values);

}  // namespace luxel
