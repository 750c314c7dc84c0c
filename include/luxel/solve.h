// Solving diffuse interreflection on a SurfaceSet: one interface for every solver and backend.
//
// The discrete system is B_e = E_e + rho_e * (H0_e + sum_p F[e <- p] B_p), where e runs over
// elements, p over patches, B_p is the area-weighted mean radiosity of the patch's elements, and
// H0_e is the irradiance from analytic lights. Every solver solves this same system, so they agree
// to their convergence tolerance. Radiosity B is exitance (W/m^2); radiance is B / pi.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "luxel/progress.h"
#include "luxel/scene.h"
#include "luxel/surface.h"

namespace luxel {

struct FormFactorOptions {
  // Visibility rays per element-patch pair; rounded down to a square (1, 4, 9, 16, ...).
  int raysPerPair = 4;
  // Rays for pairs closer than `nearFactor` times their summed sizes, where both the unoccluded
  // form factor and the visibility vary most over the receiver (contacts, corners).
  int nearRaysPerPair = 16;
  // Rays for pairs whose source patch emits: direct light makes the sharpest shadows, and their
  // noise was the largest share of the error against a converged reference (Cornell box, 10k
  // elements: NRMSE 0.013 at 16 rays, 0.0064 at 64). Shaft culling leaves only penumbra pairs.
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

// Patches a progressive pass shoots together (SolveOptions::shootersPerPass): at most, and by
// default.
inline constexpr int kMaxShootersPerPass = 32;
inline constexpr int kDefaultShootersPerPass = 8;

struct SolveOptions {
  enum class Method { Progressive, Gather };
  Method method = Method::Progressive;

  // Where form factors are computed: the CPU (Embree + TBB), the GPU (OpenGL 4.5 hemicubes
  // through EGL, headless), or the GPU when a context can be made and the CPU otherwise (with a
  // warning in SolveStats::warnings).
  enum class Backend { Cpu, Gl, Auto };
  Backend backend = Backend::Cpu;
  // GL backend: hemicubes of `resolution` top-face pixels a side, `perSide` x `perSide` of them
  // spread over each shooting patch (progressive; seed 001 renders 64-pixel ID hemicubes) or over
  // each receiving element (gather, where the hemicube's pixels are the form factors' only
  // resolution, so it needs more of them).
  struct HemicubeSampling {
    int resolution;
    int perSide;
  };
  HemicubeSampling shootingHemicubes{64, 3};
  HemicubeSampling gatheringHemicubes{256, 2};
  // GL progressive: an emitting patch's first shot, the direct light with its penumbrae, spreads
  // K x K hemicubes over the patch instead of shootingHemicubes.perSide (seed 001's dynamic
  // shooter subdivision: more, smaller shooters where much radiosity is shot). 0: the same.
  int emitterHemicubesPerSide = 6;
  // GL progressive shooting: how a shooter's hemicube tells whether it sees a point: by the id of
  // the nearest face (seed 001's ID hemicube; the default) or by the distance to it (seed 003's
  // depth hemicube, with the face id as a fallback for surfaces seen edge-on). Measured against
  // converged CPU references (64 pixels, 3 x 3 per patch, 6 x 6 on emitters): the Cornell box at
  // 1,500 elements 0.0104 NRMSE by id, 0.0090 by depth; the indirect-light room converged, 0.0065
  // by id and 0.057 by depth (light through its 20 cm walls).
  enum class HemicubeVisibility { Item, Distance };
  HemicubeVisibility hemicubeVisibility = HemicubeVisibility::Item;

  // progressive: stop when unshot power / emitted power falls below this...
  double unshotThreshold = 1e-3;
  // ...or after this many seconds or shots (0: no limit).
  double timeBudget = 0.0;
  uint64_t shotBudget = 0;
  // progressive: patches shot together, the most unshot power first, in one pass over the
  // receivers (1..32; 0: 8 on the CPU and on a GPU, 1 on a software rasteriser, where a pass
  // has no fixed cost worth sharing and larger batches only shoot staler choices: cornell-low
  // 382 shots in 1.25 s at 1, 418 in 1.53 s at 8 on llvmpipe; docs/performance.md).
  int shootersPerPass = 0;
  // Add Cohen et al.'s ambient term to the returned radiosity (display estimate of what is unshot).
  bool ambient = true;

  // gather: Gauss-Seidel (or Jacobi) until the largest relative change is below this.
  double residualThreshold = 1e-5;
  int maxIterations = 10000;
  bool gaussSeidel = true;

  // Adaptive refinement: split elements whose radiosity differs from a neighbour's by more than
  // `refineThreshold` (relative) and re-solve, until `refineBudget` extra elements are used.
  size_t refineBudget = 0;
  float refineThreshold = 0.15f;
  int maxRefineDepth = 3;

  FormFactorOptions formFactors;
};

struct SolveStats {
  std::string method;
  std::string backend;                // "cpu" or "gl"
  std::string device;                 // the GL renderer when backend is "gl"
  std::vector<std::string> warnings;  // e.g. why --backend auto fell back to the CPU
  size_t elements = 0;
  size_t patches = 0;
  uint64_t shots = 0;          // progressive: patches shot
  uint64_t iterations = 0;     // gather: sweeps
  uint64_t rays = 0;           // visibility rays traced
  uint64_t hemicubes = 0;      // GL backend: hemicubes rendered
  double residual = 0.0;       // gather: last relative change; progressive: unshot fraction
  double unshotFraction = 0.0;
  double secondsSetup = 0.0;        // BVH build, analytic lights
  double secondsFormFactors = 0.0;  // form factors and visibility
  double secondsSolve = 0.0;        // iterations / shooting bookkeeping
  double secondsTotal = 0.0;
  size_t refinedElements = 0;
  int refinePasses = 0;
  double emittedPower = 0.0;   // W: sum of A E plus analytic-light power reaching surfaces
  double absorbedPower = 0.0;  // W: sum of A (1 - rho) H
  double raysPerSecond() const { return secondsFormFactors > 0 ? double(rays) / secondsFormFactors : 0; }
};

struct Solution {
  std::vector<Rgb> radiosity;          // B per element (exitance), ambient term included if asked
  std::vector<Rgb> irradiance;         // H per element: all light arriving, both sides
  std::vector<Rgb> directIrradiance;   // the part of H that comes straight from emitters and lights
  SolveStats stats;
};

// Solves on the CPU backend (Embree + TBB). `surfaces` may be refined in place when
// options.refineBudget > 0. Throws Error on bad options, Cancelled when `progress` says stop.
Solution solve(const Scene& scene, SurfaceSet& surfaces, const SolveOptions& options,
               const ProgressCallback& progress = {});

SolveOptions::Method parseSolveMethod(const std::string& name);    // "progressive" | "gather"
SolveOptions::Backend parseSolveBackend(const std::string& name);  // "cpu" | "gl" | "auto"
SolveOptions::HemicubeVisibility parseHemicubeVisibility(const std::string& name);  // "item" | "distance"

}  // namespace luxel
