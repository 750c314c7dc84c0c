// Direct light at a surface point, for per-pixel shading: emitting polygons by their exact
// unoccluded form factor F (Baum et al. 1989) less what a shadow ray finds blocked, analytic
// lights by sampleLight(). For an emitter, a point y drawn uniformly over its part in front of
// the receiver gives F - A k(y) (1 - V(y)), A that part's area and k the point-to-point kernel
// cos cos / (pi r^2): exact when nothing is in the way, and unbiased when something is. The
// simpler F V(y) weights every point of the emitter alike, and comes out low where the blocked
// part is the part the kernel favours (docs/algorithms.md, "Rendering", has the measurements).
// Emitting faces are used whole where their emission is uniform, element by element where it
// varies (transport/emitting_polygons.h).
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "core/random.h"
#include "luxel/scene.h"
#include "luxel/surface.h"
#include "trace/ray_tracer.h"
#include "transport/form_factor.h"
#include "transport/light_sampling.h"

namespace luxel {

// sample()'s `element` when the point is on none of the receivers' elements.
inline constexpr uint32_t kNoElement = 0xffffffffu;

class DirectLight {
 public:
  // `receivers`: the elements whose indices sample() is given (none when null). With them, each
  // element's view of each emitter is shaft-culled on first demand (Haines and Wallace 1991, as
  // the transport does between patches): where no face reaches into the hull of the two, every
  // point of the element sees all of the emitter, so its light there is the exact factor F, with
  // no shadow ray. Scenes of many small faces put more faces in a shaft than are worth testing
  // (the transport's limit), so there nothing is culled and receivers are not kept.
  // `skies` false: the scene's skies are left out (an hq render's vertex gather takes their light
  // instead, render/final_gather.h).
  DirectLight(const Scene& scene, const SurfaceSet& surfaces, const SurfaceSet* receivers = nullptr,
              bool skies = true);
  ~DirectLight();
  DirectLight(const DirectLight&) = delete;
  DirectLight& operator=(const DirectLight&) = delete;

  // One sample: appends shadow rays and the irradiance each brings if unoccluded, and returns the
  // irradiance that comes whatever the rays find (which may be negative).
  Rgb sample(Vec3 x, Vec3 n, Sides sides, Rng& rng, float rayOffset, std::vector<RTCRay>& rays,
             std::vector<Rgb>& values) const {
    return sample(x, n, n, sides, rng, rayOffset, rays, values);
  }
  // The same with the point of each light's area (or solid angle) taken from `u`, a stratified
  // sample (core/multi_jitter.h), so that a pixel's samples cover a lamp evenly and penumbrae come
  // out smooth; `rng` draws the rest (emitters by power, retries behind the receiver's plane).
  // `element`: the receivers' element x lies on, or kNoElement.
  Rgb sample(Vec3 x, Vec3 n, Vec3 shading, Sides sides, Vec2 u, Rng& rng, float rayOffset,
             std::vector<RTCRay>& rays, std::vector<Rgb>& values, uint32_t element = kNoElement) const {
    return sample(x, n, shading, sides, std::span<const Vec2>(&u, 1), rng, rayOffset, rays, values, element);
  }
  // The sum of the samples at each of `points`, one light point each: the emitters' factors at x
  // are found once for all of them.
  Rgb sample(Vec3 x, Vec3 n, Vec3 shading, Sides sides, std::span<const Vec2> points, Rng& rng, float rayOffset,
             std::vector<RTCRay>& rays, std::vector<Rgb>& values, uint32_t element = kNoElement) const;
  // The same with a shading normal (a normal map's, render/normal_map.h) for the receiver's cosine,
  // max(0, shading . l): the irradiance a surface of that orientation would get. Shadow rays leave
  // from the geometric surface (offset along n), and with Sides::Front light from behind its
  // geometric plane counts as occluded, since the surface itself is in the way. With shading == n
  // this is the call above, sample for sample.
  Rgb sample(Vec3 x, Vec3 n, Vec3 shading, Sides sides, Rng& rng, float rayOffset, std::vector<RTCRay>& rays,
             std::vector<Rgb>& values) const {
    const Vec2 u(rng.next(), rng.next());
    return sample(x, n, shading, sides, u, rng, rayOffset, rays, values);
  }

 private:
  struct Emitter {
    Polygon polygon;
    Vec3 normal;
    float area;
    Rgb exitance;
    Sides sides;
  };
  // `whole`: x's element sees all of the emitter (a clear shaft), so nothing blocks it.
  // Each of `points` rotated by `rotation` (so that each light takes its own stratification).
  Rgb sampleEmitter(const Emitter& em, float weight, Vec3 x, Vec3 n, Vec3 shading, Sides sides,
                    std::span<const Vec2> points, size_t rotation, Rng& rng, float rayOffset,
                    std::vector<RTCRay>& rays, std::vector<Rgb>& values, bool whole) const;
  // Whether element `element` of the receivers sees all of emitter k (decided once, then cached).
  bool seesWhole(uint32_t element, size_t k) const;
  struct Shafts;
  std::unique_ptr<Shafts> shafts_;

  const Scene& scene_;
  std::vector<PreparedLight> lights_;  // the scene's lights, each prepared once for every sample
  bool skies_ = true;
  Vec3 up_;
  std::vector<Emitter> emitters_;
  std::vector<float> cdf_;  // by power, for scenes with many emitters
};

}  // namespace luxel
