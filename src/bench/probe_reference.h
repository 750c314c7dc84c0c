// The benchmark's independent judge: the irradiance at fixed probe elements, path traced
// (transport/path_traced_irradiance.h) rather than solved, so that a solver and the reference
// solution it is scored against can both be checked against something that shares none of their
// discretisation. Cached on disk like the references (bench/reference.h).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "luxel/bench.h"
#include "luxel/progress.h"
#include "luxel/scene.h"
#include "transport/path_traced_irradiance.h"

namespace luxel::bench {

struct ProbeReference {
  std::vector<uint32_t> elements;
  std::vector<ElementIrradianceEstimate> estimates;  // one per element above
  double seconds = 0.0;                              // 0 when it came from the cache
  std::string path;                                  // the cache file
};

// `count` elements that do not emit, drawn by area (stratified over the elements' running area
// from a fixed seed, so the same surfaces give the same probes), each at most once.
std::vector<uint32_t> chooseProbeElements(const SurfaceSet& surfaces, size_t count);

// The probes of chooseProbeElements(surfaces, count), path traced with `options`, from `cacheDir`
// when a file there was made from the same elements, lights and options.
ProbeReference loadOrComputeProbes(const Scene& scene, const SurfaceSet& surfaces, const std::string& cacheDir,
                                   size_t count, const PathTracingOptions& options,
                                   const ProgressCallback& progress);

// The light `whole` has and `part` does not (the indirect light: every bounce less the direct
// light), with both estimates' noise. Throws Error unless both are of the same elements.
ProbeReference probeDifference(const ProbeReference& whole, const ProbeReference& part);

// Element irradiance from radiosity, H = (B - E) / rho per channel, NaN where rho is 0: the
// cached references keep radiosity only.
std::vector<Rgb> irradianceFromRadiosity(const SurfaceSet& surfaces, std::span<const Rgb> radiosity);

// How far `irradiance` (per element) is from the probes. NaN channels are left out.
ProbeError probeError(const ProbeReference& probes, std::span<const Rgb> irradiance);

}  // namespace luxel::bench
