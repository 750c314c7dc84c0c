// What a solver produces: radiosity, irradiance and direct irradiance per element, and the
// statistics of how it got there. Radiosity B is exitance (W/m^2); radiance is B / pi.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "luxel/scene.h"

namespace luxel {

// One phase of a solver's work (GL solvers: gl/gpu_timeline.h), summed over its occurrences.
struct PhaseTime {
  std::string name;
  uint64_t count = 0;
  double secondsGpu = 0.0;  // between GL timestamps bracketing it: the GPU's own time
  double secondsCpu = 0.0;  // wall time on the CPU issuing it (driver calls and CPU work)
};

// Each phase of `after` less its part in `before` (two readings of SolveStats::phases), those
// that ran between them; a phase whose count went down (the solver started again) whole.
std::vector<PhaseTime> phasesSince(const std::vector<PhaseTime>& before, const std::vector<PhaseTime>& after);

struct SolveStats {
  std::string method;                 // the registered method, e.g. "progressive"
  std::string backend;                // "cpu" or "gl"
  std::string device;                 // the GL renderer when backend is "gl"
  std::vector<std::string> warnings;  // e.g. why --backend auto fell back to the CPU
  size_t elements = 0;
  size_t patches = 0;
  uint64_t shots = 0;          // progressive: patches shot
  uint64_t iterations = 0;     // gather: sweeps
  uint64_t rays = 0;           // visibility rays traced
  uint64_t hemicubes = 0;      // GL backend: hemicubes rendered
  uint64_t links = 0;          // hierarchical: transfers computed (links are not stored)
  // hierarchical: link refinements over the solve, by rule: near cluster emitter, transfer
  // bound, shadow edge, self-oracle.
  std::array<uint64_t, 4> refinements{};
  size_t clusterElements = 0;  // hierarchical: clusters in the element tree
  size_t clusterLeaves = 0;    // hierarchical: its leaves, which hold the irradiance
  double secondsHierarchy = 0.0;  // hierarchical: building the face-cluster tree
  size_t hierarchyBytes = 0;      // hierarchical: the face-cluster tree's memory
  bool hierarchyCached = false;   // hierarchical: the tree was read from the disk cache
  uint32_t hierarchyDepth = 0;    // hierarchical: the tree's deepest leaf
  double hierarchyMeanLeafDepth = 0.0;
  uint64_t redistributions = 0;    // dynamic solvers: moves and light edits followed
  uint64_t factorsRecomputed = 0;  // dynamic solvers: element-patch factors computed again for them
  double secondsRedistribution = 0.0;  // dynamic solvers: the corrections (new factors included)
  double residual = 0.0;       // gather: last relative change; progressive: unshot fraction
  double unshotFraction = 0.0;
  double secondsSetup = 0.0;        // BVH build, GL context, analytic lights, solver setup
  double secondsFormFactors = 0.0;  // form factors and visibility
  double secondsSolve = 0.0;        // iterations / shooting bookkeeping
  double secondsTotal = 0.0;
  size_t refinedElements = 0;
  int refinePasses = 0;
  std::vector<PhaseTime> phases;  // GL progressive solvers: time by phase, cumulative
  double emittedPower = 0.0;   // W: sum of A E plus analytic-light power reaching surfaces
  double absorbedPower = 0.0;  // W: sum of A (1 - rho) H
  double raysPerSecond() const { return secondsFormFactors > 0 ? double(rays) / secondsFormFactors : 0; }
};

struct Solution {
  std::vector<Rgb> radiosity;          // B per element (exitance), ambient term included if asked
  std::vector<Rgb> irradiance;         // H per element: all light arriving, both sides
  std::vector<Rgb> directIrradiance;   // the part of H that comes straight from emitters and lights
  // Unshot radiosity per element (progressive shooting, on either backend, and the dynamic solvers
  // built on it: what is still to be shot, W/m^2), for a heat map of where the solve has work left;
  // empty for methods that keep none (gathering, the hierarchy).
  std::vector<Rgb> unshot;
  SolveStats stats;
};

}  // namespace luxel
