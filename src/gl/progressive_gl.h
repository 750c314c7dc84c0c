// Progressive refinement radiosity on the GPU, resident there from the first shot to the last
// (van de Hoef 2013, seed 001 section 4.3, after Coombe, Harris and Lastra 2004; seed 003's texel
// shooting with depth hemicubes). Per pass, with no read-back of the solution:
//   1. a compute pass sums each patch's unshot power;
//   2. one work group chooses the patches with the most (001 chose one by a mip chain and a
//      1x1 depth test, then read it back: the stall this avoids) and writes their hemicube
//      centres and mean unshot radiosity into a buffer;
//   3. each chosen patch renders k x k hemicubes at stratified points on it (001's dynamic
//      shooter subdivision, fixed to k x k here), centres read from that buffer;
//   4. a compute pass, one thread per element, gathers what the pass shot to it: the exact
//      unoccluded point-to-patch factor (Lambert's formula, where 001 used a disk approximation
//      that it had to subdivide near the shooter) times the share of the k x k hemicubes that
//      see the element: by its face id in the item layer (001's ID hemicube, four nearest
//      pixels), or by distance in the depth layer (003).
// The CPU reads a few bytes every few passes to learn whether to stop.
#pragma once

#include "luxel/solve.h"
#include "solve/radiosity_system.h"

namespace luxel::gl {

struct GlProgressiveOptions {
  SolveOptions::HemicubeVisibility visibility = SolveOptions::HemicubeVisibility::Item;
  int resolution = 64;          // hemicube top face, pixels a side
  int samplesPerSide = 2;       // k: k x k hemicubes per shooting patch
  // An emitting patch's first shot, which carries the direct light and its penumbrae, uses
  // k_e x k_e hemicubes (001's "dynamic shooter subdivision": more, smaller shooters where much
  // radiosity is shot). 0: k.
  int emitterSamplesPerSide = 0;
  int shootersPerPass = 8;      // patches shot together (at most kMaxShootersPerPass)
  int passesPerCheck = 4;       // passes between read-backs of the convergence state
  float nearPlane = 1e-4f;      // relative to the scene extent
  float offset = 1e-4f;         // hemicube centres lifted off the patch, relative to the extent
};

// Solves `system` as solveProgressive does (same stopping rules, ambient term and outputs), on
// the current OpenGL 4.5 context. stats.hemicubes counts the hemicubes of real shooters.
Solution solveProgressiveGl(const RadiositySystem& system, const SolveOptions& options,
                            const GlProgressiveOptions& gl, const ProgressCallback& progress,
                            double& formFactorSeconds);

}  // namespace luxel::gl
