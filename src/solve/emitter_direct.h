// The light each element receives straight from the emitting surfaces, computed per element as
// the analytic lights' is (transport/cpu_transport.h) rather than through a solver's coarse
// links. For each element and emitting polygon: the exact unoccluded form factor averaged over
// 2 x 2 stratified points of the element (Baum et al. 1989, the SIMD form of
// transport/form_factor.h), times the kernel-weighted share of shadow rays that arrive: 4 x 4
// first rays (element and emitter strata crossed), and 64 more where those disagree (a shadow's
// edge crosses the element). The face-cluster solver starts from it, as progressive shooting
// starts from emitters shot with dense rays (docs/algorithms.md, "Face-cluster radiosity").
#pragma once

#include <cstdint>
#include <vector>

#include "luxel/surface.h"
#include "trace/ray_tracer.h"

namespace luxel {

struct EmitterDirectLight {
  std::vector<Rgb> irradiance;  // per element, W/m^2
  // Per element, `shCount` coefficients of the incident radiance (spherical harmonics, as
  // Solver::incidentSh gives them), each emitter's light along its irradiance vector; empty
  // when none were asked for.
  std::vector<Rgb> sh;
  uint64_t rays = 0;
};

// Emitting polygons beyond this many are too many to visit from every element: emitterDirectLight
// refuses them (its caller takes their light another way).
inline constexpr size_t kMaxEmittingPolygons = 256;

// How many emitting polygons `surfaces` has: a face whose elements all carry one exitance is one,
// otherwise each of its emitting elements is.
size_t emittingPolygonCount(const SurfaceSet& surfaces);

// Every element's direct irradiance from the emitting surfaces (none: all zero), tracing against
// `tracer` (whose primitives need not be the elements). `shCount`: 0, or 4 for L1 directions.
// Deterministic for a seed; parallel over elements. Throws Error past kMaxEmittingPolygons.
EmitterDirectLight emitterDirectLight(const SurfaceSet& surfaces, const RayTracer& tracer, int shCount, uint32_t seed);

}  // namespace luxel
