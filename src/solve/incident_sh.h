// Where interreflected light comes from, for directional lightmaps (issue 17, seed 004 section 4):
// the spherical-harmonic projection (core/spherical_harmonics.h) of the radiance a patch sends an
// element, from the form factor a solver already has.
#pragma once

#include "luxel/surface.h"

namespace luxel {

// Adds to c (count = 4 or 9 coefficients) the incident radiance that patch `p` of exitance `b`
// brings element `e` through the form factor `f` (visibility included). Bands 0 and 1 are the
// exact moments of the patch's polygon as seen from the element's centroid (its solid angle, Van
// Oosterom and Strackee, and its irradiance vector, Arvo 1994), scaled by the visible share
// f / (unoccluded factor); band 2 from pieces of the polygon, each taken as one direction, more of
// them the nearer the patch.
// The solid angle is of the whole polygon where the element's plane cuts it: a small excess in
// band 0, which the renormalisation to the texel's irradiance at display absorbs.
void addPatchSh(const SurfaceSet& surfaces, uint32_t e, uint32_t p, float f, Rgb b, int count, Rgb* c);

}  // namespace luxel
