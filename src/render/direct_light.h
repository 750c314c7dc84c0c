// Direct light at a surface point, for per-pixel shading: emitting polygons by their exact
// unoccluded form factor times a shadow ray (Baum et al. 1989), analytic lights by sampleLight().
// Emitting faces with uniform emission are used whole; faces with an emission texture are used
// element by element so the texture's variation is kept.
#pragma once

#include <vector>

#include "core/random.h"
#include "luxel/scene.h"
#include "luxel/surface.h"
#include "trace/ray_tracer.h"
#include "transport/form_factor.h"

namespace luxel {

class DirectLight {
 public:
  DirectLight(const Scene& scene, const SurfaceSet& surfaces);

  // Appends one sample's shadow rays and the irradiance each brings if unoccluded.
  void sample(Vec3 x, Vec3 n, Sides sides, Rng& rng, float rayOffset, std::vector<RTCRay>& rays,
              std::vector<Rgb>& values) const {
    sample(x, n, n, sides, rng, rayOffset, rays, values);
  }
  // The same with the point of each light's area (or solid angle) taken from `u`, a stratified
  // sample (core/multi_jitter.h), so that a pixel's samples cover a lamp evenly and penumbrae come
  // out smooth; `rng` draws the rest (emitters by power, retries behind the receiver's plane).
  void sample(Vec3 x, Vec3 n, Vec3 shading, Sides sides, Vec2 u, Rng& rng, float rayOffset,
              std::vector<RTCRay>& rays, std::vector<Rgb>& values) const;
  // The same with a shading normal (a normal map's, render/normal_map.h) for the receiver's cosine,
  // max(0, shading . l): the irradiance a surface of that orientation would get. Shadow rays leave
  // from the geometric surface (offset along n), and with Sides::Front light from behind its
  // geometric plane counts as occluded, since the surface itself is in the way. With shading == n
  // this is the call above, sample for sample.
  void sample(Vec3 x, Vec3 n, Vec3 shading, Sides sides, Rng& rng, float rayOffset, std::vector<RTCRay>& rays,
              std::vector<Rgb>& values) const {
    const Vec2 u(rng.next(), rng.next());
    sample(x, n, shading, sides, u, rng, rayOffset, rays, values);
  }

 private:
  struct Emitter {
    Polygon polygon;
    Rgb exitance;
    Sides sides;
  };
  void sampleEmitter(const Emitter& em, float weight, Vec3 x, Vec3 n, Vec3 shading, Sides sides, Vec2 u,
                     Rng& rng, float rayOffset, std::vector<RTCRay>& rays, std::vector<Rgb>& values) const;

  const Scene& scene_;
  Vec3 up_;
  std::vector<Emitter> emitters_;
  std::vector<float> cdf_;  // by power, for scenes with many emitters
};

}  // namespace luxel
