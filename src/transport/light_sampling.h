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

// Radiance of a sky light in direction `w` (unit), 0 below the horizon.
Rgb skyRadiance(const Light& light, Vec3 w, Vec3 up);

// True for lights at infinity whose shadow rays are unbounded (sun and skies).
bool isDistantLight(const Light& light);

// True for the skies, which light the whole hemisphere.
bool isSkyLight(const Light& light);

}  // namespace luxel
