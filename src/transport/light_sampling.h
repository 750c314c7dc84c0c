// Sampling the analytic lights (point, spot, sun, uniform sky, CIE overcast sky) from a surface
// point. The same sampler serves the solver (irradiance averaged over elements) and the renderer
// (direct light per pixel), so both see the same lights.
#pragma once

#include "luxel/scene.h"
#include "transport/form_factor.h"

namespace luxel {

struct LightSample {
  Rgb irradiance{0.0f};  // unoccluded irradiance estimate (already divided by the pdf)
  Vec3 direction{0.0f};  // towards the light; the shadow ray is x + t * direction, t in (0, tfar)
  float tfar = 0.0f;
  bool valid() const { return irradiance.r > 0.0f || irradiance.g > 0.0f || irradiance.b > 0.0f; }
};

// One sample of the irradiance `light` gives the point `x` with unit normal `n`; (u1, u2) are
// uniform in [0,1). With Sides::Both the point receives from both hemispheres.
LightSample sampleLight(const Light& light, Vec3 x, Vec3 n, Sides sides, Vec3 up, float u1, float u2);

// What every sample of a light computes the same way, computed once for many samples (an
// element's): its power, a spot's cone, the sun's cone and the frame about its axis. It refers to
// `light`, which must outlive it. Samples from it are the same numbers as sampleLight's.
struct PreparedLight {
  const Light* light = nullptr;
  Rgb power{0.0f};
  Vec3 axis{0.0f}, t{0.0f}, b{0.0f};  // spot: its direction; sun: towards it, and a frame about it
  float cosMax = 1.0f;                 // sun: cosine of its angular radius
  float cosOuter = 0.0f, cosInner = 1.0f;  // spot
};
PreparedLight prepareLight(const Light& light);
LightSample sampleLight(const PreparedLight& light, Vec3 x, Vec3 n, Sides sides, Vec3 up, float u1, float u2);

// False when no sample of `light` can light the front of `polygon` (normal `n`): a sun whose whole
// disc is behind its plane, a lamp behind every corner. Skies may always. Lets a caller skip an
// element's samples, which would all be dark, before drawing them.
bool lightMayReachFront(const Light& light, const Polygon& polygon, Vec3 n);

// Radiance of a sky light in direction `w` (unit), 0 below the horizon.
Rgb skyRadiance(const Light& light, Vec3 w, Vec3 up);

// True for lights at infinity whose shadow rays are unbounded (sun and skies).
bool isDistantLight(const Light& light);

// True for the skies, which light the whole hemisphere.
bool isSkyLight(const Light& light);

}  // namespace luxel
