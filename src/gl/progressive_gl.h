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
// The CPU reads a few bytes every few passes to learn whether to stop. With followChanges, a
// move or an edit is followed by redistribution instead of a new solve (progressive_gl.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "gl/cross_redistribution_settings.h"
#include "luxel/solver.h"
#include "solve/radiosity_system.h"

namespace luxel::gl {

class Context;

// How a shooter's hemicube tells whether it sees a point: by the id of the nearest face (seed
// 001's ID hemicube; the default) or by the distance to it (seed 003's depth hemicube, with the
// face id as a fallback for surfaces seen edge-on). docs/performance.md compares them.
enum class HemicubeVisibility { Item, Distance };

struct GlProgressiveSettings {
  HemicubeVisibility visibility = HemicubeVisibility::Item;
  int resolution = 64;          // hemicube top face, pixels a side
  HemicubeLayering layering = HemicubeLayering::Auto;
  int samplesPerSide = 3;       // k: k x k hemicubes per shooting patch
  // An emitting patch's first shot, which carries the direct light and its penumbrae, uses
  // k_e x k_e hemicubes (001's "dynamic shooter subdivision": more, smaller shooters where much
  // radiosity is shot). 0: k.
  int emitterSamplesPerSide = 6;
  int shootersPerPass = 8;      // patches shot together (at most kMaxShootersPerPass)
  int passesPerCheck = 4;       // passes between read-backs of the convergence state
  float nearPlane = 1e-4f;      // relative to the scene extent
  float offset = 1e-4f;         // hemicube centres lifted off the patch, relative to the extent
  // Follow moves, light and material edits by redistribution (the incremental method of seed
  // 001, section 4.4: every patch shoots what it has shot again, negated from where everything
  // was and from where everything is), instead of asking to be replaced.
  bool followChanges = false;
  // With followChanges: follow moves by cross-redistribution instead (seed 001 section 4.5,
  // cross_redistribution_gl.h): only the moved patches render hemicubes.
  bool crossRedistribution = false;
  CrossRedistributionSettings cross;
  // Following changes: with nothing moving, each further step goes a decade below the unshot
  // threshold, down to this (the CPU's dynamic solvers do the same).
  double settleThreshold = 1e-5;
  // Stopping rules and display, as the CPU's progressive solver.
  double unshotThreshold = 1e-3;
  double timeBudget = 0.0;
  uint64_t shotBudget = 0;
  bool ambient = true;
};

// A solver of `system` as the CPU's progressive solver (same stopping rules, ambient term and
// outputs), on `context`, which must be current and outlive it. stats.hemicubes counts the
// hemicubes of real shooters. Cross-redistribution needs `objectOfPatch`, each patch's scene
// object. Throws Error on settings out of range.
std::unique_ptr<Solver> makeGlProgressiveSolver(const RadiositySystem& system, Context& context,
                                                const GlProgressiveSettings& settings,
                                                std::vector<uint32_t> objectOfPatch = {});

}  // namespace luxel::gl
