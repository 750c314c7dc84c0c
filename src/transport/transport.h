// The boundary between the CPU solvers and the form factors they use: in batches, never one ray at
// a time. A solver asks for whole columns (everything a set of patches shoots into) or whole rows
// (everything a set of elements gathers from); CpuTransport maps them onto Embree ray streams on
// TBB threads, MonteCarloTransport onto cosine-distributed rays. The GPU backend's solvers keep
// their form factors on the GPU (they are solvers of their own in the registry) and take only the
// analytic lights from here.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "luxel/scene.h"

namespace luxel {

class RayTracer;

// The smallest receiver cosine a sample's irradiance is divided by to become radiance times solid
// angle (Transport::lightSh).
inline constexpr float kShMinimumCosine = 0.05f;

// The reaches a move's certificates are given at (Transport::visibilityChangedByMove).
inline constexpr int kCertificateLevels = 4;

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

  // The same form factors for any (element, patch) pairs: out[i] = F[pairs[i].element <- pairs[i].patch],
  // the number columns() and rows() give that pair.
  struct ElementPatch {
    uint32_t element, patch;
  };
  virtual void pairs(std::span<const ElementPatch> pairs, std::span<float> out) = 0;

  // Irradiance at each element from the scene's analytic lights (point, spot, sun, skies),
  // with shadows, averaged over the element.
  virtual void analyticIrradiance(std::span<Rgb> out) = 0;
  // The part of analyticIrradiance that the lights `lights` (indices into Scene::lights) bring:
  // the same samples, so the parts of every light add up to the whole (a viewer that shows some
  // lights per pixel takes their part out of the interpolated field).
  virtual void lightIrradiance(std::span<const uint32_t> lights, std::span<Rgb> out) = 0;
  // Where that light comes from: the incident radiance of the lights `lights` at each element in
  // spherical harmonics (core/spherical_harmonics.h), `count` (4 or 9) coefficients per element,
  // out[e * count + i]. The same samples as lightIrradiance: each one that reaches the element
  // adds its irradiance / cos(theta) along its direction (cos clamped at kShMinimumCosine, so that
  // sky samples at the horizon do not explode). Throws Error where the backend cannot.
  virtual void lightSh(std::span<const uint32_t> lights, int count, std::span<Rgb> out);
  // Both at once, for owners that want the directions from the start (a directional bake): the
  // default asks for each in turn; a transport that traces does it with one set of rays.
  virtual void lightIrradianceAndSh(std::span<const uint32_t> lights, int count, std::span<Rgb> irradiance,
                                    std::span<Rgb> sh) {
    lightIrradiance(lights, irradiance);
    lightSh(lights, count, sh);
  }

  // The ray tracer over the scene's faces, for solvers that trace their own rays (the
  // hierarchical solver); null where the backend has none.
  virtual RayTracer* rayTracer() { return nullptr; }

  // Rays traced so far (0 for backends that do not trace rays).
  virtual uint64_t raysTraced() const = 0;

  // The elements changed (adaptive refinement split some); patches and faces did not. Backends
  // rebuild whatever they keep per element.
  virtual void elementsChanged() = 0;

  // Dynamic objects of the scene moved (Scene::placeObject and SurfaceSet::placeObject have put
  // the scene and the surfaces this transport was built over in their new places). Backends
  // update what depends on where those objects are, and keep the rest. Throws Error where a
  // backend cannot follow moves.
  virtual void objectsMoved(std::span<const uint32_t> objects) = 0;

  // The surfaces' emission changed (SurfaceSet::refreshMaterials after a material edit).
  // Backends update what they derived from it; patchesRedoneBySources() then lists the patches
  // whose factors it changed (CpuTransport: patches that started or stopped emitting, whose pairs
  // take a different number of rays). Solvers that keep factors recompute those columns.
  virtual void sourcesChanged() {}
  virtual std::vector<uint32_t> patchesRedoneBySources() const { return {}; }

  // After objectsMoved: elements whose factors from every patch the last move changed for reasons
  // of the backend's own besides visibility (CpuTransport: receiver quadratures made denser or
  // coarser near the moved faces). Solvers that keep factors across moves recompute these.
  virtual std::vector<uint32_t> receiversRedoneByMove() const { return {}; }

  // After objectsMoved: for each (element, patch) pair of static surfaces, whether the move can
  // have changed its factor's visibility, that is whether one of its visibility rays meets the
  // moved objects in one of their two places (before and after the move) and not in the other.
  // 0 promises the factor is the same number as before the move, for receivers not in
  // receiversRedoneByMove. Backends that cannot tell say 1.
  // With `certify` > 0 and a `certified` span, also sets certified[i] to k > 0 when pair i's rays
  // keep their verdicts for the moved objects anywhere within `certify` * 2^(k - 1) of where
  // they were before this move (every corner moved less), for the largest such k up to
  // kCertificateLevels: a solver may skip the pair while the objects stay that near. 0: no such
  // promise (backends that cannot tell say 0).
  virtual void visibilityChangedByMove(std::span<const ElementPatch> pairs, std::span<uint8_t> changed,
                                       float certify = 0.0f, std::span<uint8_t> certified = {}) {
    (void)pairs, (void)certify;
    std::fill(changed.begin(), changed.end(), uint8_t(1));
    std::fill(certified.begin(), certified.end(), uint8_t(0));
  }

  // After objectsMoved: brings `irradiance`, the part of analytic irradiance that the lights
  // `lights` gave each element before the move (lightIrradiance), up to the new places: what
  // lightIrradiance would now return. Backends that can tell which elements the move cannot have
  // changed keep theirs. Returns how many elements were computed again.
  virtual size_t updateLightIrradianceAfterMove(std::span<const uint32_t> lights, std::span<Rgb> irradiance) {
    lightIrradiance(lights, irradiance);
    return irradiance.size();
  }
};

}  // namespace luxel
