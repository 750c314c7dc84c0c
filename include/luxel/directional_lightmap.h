// Directional lightmaps (issue 17; seed 004 section 4): besides the irradiance H at the surface's
// own normal, each texel keeps where its light comes from, so that a normal map under the
// lightmap shades as the light arrives. The bake records the incident radiance in real spherical
// harmonics (the solver's shots and the lights' samples, src/solve/incident_sh.h); a mode says
// what is kept and how it is read back. docs/baking.md, "Directional lightmaps", has the formats.
#pragma once

#include <string>

#include "luxel/scene.h"

namespace luxel {

enum class DirectionalMode {
  None,
  // L1: 4 coefficients per channel, read as a constant plus one directional light per channel
  // (Sloan 2008), which is exact for one lamp and never negative.
  ShL1,
  // L2: 9 coefficients per channel, read linearly (Ramamoorthi and Hanrahan 2001), windowed at the
  // bake so that no texel's irradiance is negative for any normal.
  ShL2,
  // One direction per texel for all channels (the luminance's L1 vector) and how directional the
  // light is: the L1 reading with a shared direction, a third of the L1 storage.
  Dominant,
};

inline constexpr int kMaxDirectionalCoefficients = 9;

// "none", "sh-l1", "sh-l2", "dominant"; throws Error listing them for anything else.
DirectionalMode parseDirectionalMode(const std::string& name);
const char* directionalModeName(DirectionalMode mode);
// Coefficients per channel the bake records: 0, 4, 9 and 4.
int directionalCoefficients(DirectionalMode mode);

// The irradiance at unit shading normal n of a texel whose irradiance at its geometric normal n0
// is h, from its `directionalCoefficients(mode)` coefficients c: the mode's reading, scaled so that
// it gives h exactly at n0 (the plain lightmap stays the truth at the surface's own normal; the
// direction only says how it changes as the normal turns). h at any n when the reading at n0 is 0.
Rgb directionalIrradiance(DirectionalMode mode, const Rgb* c, Rgb h, Vec3 n0, Vec3 n);

// ---- The 8-bit encoding of the glb's LUXEL_lightmap_directional extension (docs/baking.md) ----
// Every texel's coefficients relative to its band 0, per channel, so that the plain lightmap keeps
// the scale and the direction textures only the shape: q_i = c_i / c_0, i >= 1, each stored as
// 0.5 + 0.5 q_i / bound_i, where bound_i is the largest |Y_i / Y_0| (sqrt 3 for band 1, sqrt 5 for
// band 2), which no light >= 0 exceeds.
//  - ShL1: 3 RGB textures, the x, y and z of the band-1 vector m1 / m0 (q_3, q_1, q_2 / sqrt 3).
//  - Dominant: 1 RGB texture, x, y, z of the luminance's m1 / m0.
//  - ShL2: 8 RGB textures, q_1 ... q_8.
// The reading divides the irradiance back out: directionalIrradiance with c_0 = 1 gives the same.
int directionalTextureCount(DirectionalMode mode);
// Texture k of one texel's coefficients c, as values in [0, 1] per channel (to be quantised to 8
// bits). Channels whose band 0 is <= 0 encode as 0.5 (no direction).
Rgb encodeDirectionalTexel(DirectionalMode mode, const Rgb* c, int k);
// The coefficients (c_0 = 1 per channel) the textures' values give back: the inverse of
// encodeDirectionalTexel; `values` holds directionalTextureCount(mode) colours.
void decodeDirectionalTexel(DirectionalMode mode, const Rgb* values, Rgb* c);

}  // namespace luxel
