// The boundary between solvers and backends: form factors in batches, never one ray at a time.
// A solver asks for whole columns (everything a set of patches shoots into) or whole rows
// (everything a set of elements gathers from); the CPU backend maps them onto Embree ray streams
// on TBB threads, and a GPU backend onto hemicube passes. Solvers never know which one they run on.
#pragma once

#include <cstdint>
#include <span>

#include "luxel/scene.h"

namespace luxel {

class Transport {
 public:
  virtual ~Transport() = default;

  // F[e <- p] for every element e and each patch p in `patches`: `out` holds
  // patches.size() columns of elementCount() floats, column-major. F[e <- p] is the form factor
  // from element e to patch p, including visibility, so the irradiance patch p gives e is
  // F[e <- p] * B_p.
  virtual void columns(std::span<const uint32_t> patches, std::span<float> out) = 0;

  // The same form factors by rows: `out` holds elements.size() rows of patchCount() floats.
  virtual void rows(std::span<const uint32_t> elements, std::span<float> out) = 0;

  // Irradiance at each element from the scene's analytic lights (point, spot, sun, skies),
  // with shadows, averaged over the element.
  virtual void analyticIrradiance(std::span<Rgb> out) = 0;

  // Rays traced so far (0 for backends that do not trace rays).
  virtual uint64_t raysTraced() const = 0;

  // The elements changed (adaptive refinement split some); patches and faces did not. Backends
  // rebuild whatever they keep per element.
  virtual void elementsChanged() = 0;
};

}  // namespace luxel
