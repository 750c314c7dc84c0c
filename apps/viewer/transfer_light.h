// The distant light that relights a transfer bake in the baked view (docs/baking.md, "Transfer
// lightmaps in the glb"): the sky's radiance SH as stored, scaled per channel, plus each sun's
// irradiance along where it comes from, E Y_i(-d), as luxel's distantLightSh projects suns, so the
// viewer's picture under a turned sun is `luxel render --mode lightmap --transfer N --sun-direction`.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "baked_glb.h"

namespace luxel::viewer {

// bands^2 RGB coefficients (integral of L Y_i over the sphere) of the sky times `skyScale` and the
// suns; throws luxel::Error when the sky has not bands^2 coefficients.
std::vector<Rgb> transferLightSh(const BakedGlb::TransferLight& light, Rgb skyScale = Rgb(1.0f));

// The way a sun's light travels for a sun at `azimuth` degrees from the scene's east towards its
// north and `elevation` degrees above the horizon (the `sun` action's angles), and back.
Vec3 sunTravelDirection(Vec3 sceneUp, float azimuth, float elevation);
std::pair<float, float> sunAngles(Vec3 sceneUp, Vec3 travelDirection);

// "X,Y,Z" (as `luxel render --sun-direction`) as a unit vector; "V" or "R,G,B" (not negative) as a
// colour. Throw luxel::Error naming `what` when the numbers are not that, not finite, or (the
// direction) zero.
Vec3 parseDirection(const std::string& text, const std::string& what);
Rgb parseColour(const std::string& text, const std::string& what);

}  // namespace luxel::viewer
