// Where the interreflected light comes from, for solvers that keep no record of it (the hierarchy,
// the GL backend): a final gather. From each element, stratified rays over its hemisphere find
// the element they see, whose radiance B / pi is projected on spherical harmonics along the ray
// (the classic way bakers get directional lightmaps; issue 17 asks for it "for each ray in
// gathering"). Noise falls as one over the square root of the rays; the display renormalises to
// the element's exact irradiance, so the rays set only how the light turns with the normal.
#pragma once

#include <vector>

#include "luxel/surface.h"

namespace luxel {

// Per element, `count` (4 or 9) coefficients of the incident radiance from other elements,
// radiance = radiosity / pi on their front sides (the back of a one-sided element is black; a
// two-sided face's sides are told apart by nudging each along its normal). `rays` per element,
// rounded down to a square, uniform over the hemisphere.
std::vector<Rgb> gatherIncidentSh(const SurfaceSet& surfaces, const std::vector<Rgb>& radiosity, int count, int rays);

}  // namespace luxel
