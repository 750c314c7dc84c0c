// Gathering with radiosity hemicubes on the GPU, the GPU backend's reference solver (Cohen and
// Greenberg 1985; seed 000; seed 001 section 4.2): each iteration renders, from k x k points on
// every element, the patches coloured by their current radiosity, and integrates each hemicube
// with delta form factors normalised to sum to 1 (000's multiplier tables were not: its notes,
// point 5) in a compute pass, one work group per element: no form factor is stored. Jacobi
// iteration on the discrete system of luxel/solve.h (patches shoot their area-weighted mean),
// resident on the GPU; the CPU reads two numbers per iteration, the largest change and the
// largest radiosity, to decide when to stop.
#pragma once

#include <cstddef>
#include <memory>

#include "luxel/solver.h"
#include "solve/radiosity_system.h"

namespace luxel::gl {

class Context;

struct GlGatherSettings {
  int resolution = 256;      // hemicube top face, pixels a side
  int samplesPerSide = 2;    // k: k x k hemicubes per element, averaged
  float nearPlane = 1e-4f;   // relative to the scene extent
  float offset = 1e-4f;      // hemicube centres lifted off the element, relative to the extent
  bool randomTurn = true;    // turn each hemicube about its normal (seed 001 section 4.2)
  size_t layerBytes = size_t(96) << 20;  // GPU memory for the hemicubes of one batch
  // Stopping rules, as the CPU's gather (Jacobi only).
  double residualThreshold = 1e-5;
  int maxIterations = 10000;
};

// A solver of `system` as the CPU's gather (residual threshold, iteration cap, stagnation stop;
// Jacobi only), on `context`, which must be current and outlive it. stats.hemicubes counts every
// hemicube rendered.
std::unique_ptr<Solver> makeGlGatherSolver(const RadiositySystem& system, Context& context,
                                           const GlGatherSettings& settings);

}  // namespace luxel::gl
