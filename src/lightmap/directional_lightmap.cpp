// Reading directional lightmaps back: see luxel/directional_lightmap.h.
#include "luxel/directional_lightmap.h"

#include <algorithm>

#include "core/spherical_harmonics.h"
#include "luxel/error.h"

namespace luxel {

DirectionalMode parseDirectionalMode(const std::string& name) {
  if (name == "none") return DirectionalMode::None;
  if (name == "sh-l1") return DirectionalMode::ShL1;
  if (name == "sh-l2") return DirectionalMode::ShL2;
  if (name == "dominant") return DirectionalMode::Dominant;
  throw Error("unknown directional mode '" + name + "': none, sh-l1, sh-l2 or dominant");
}

const char* directionalModeName(DirectionalMode mode) {
  switch (mode) {
    case DirectionalMode::None: return "none";
    case DirectionalMode::ShL1: return "sh-l1";
    case DirectionalMode::ShL2: return "sh-l2";
    case DirectionalMode::Dominant: return "dominant";
  }
  return "none";
}

int directionalCoefficients(DirectionalMode mode) {
  switch (mode) {
    case DirectionalMode::None: return 0;
    case DirectionalMode::ShL1: return kShL1Coefficients;
    case DirectionalMode::ShL2: return kShCoefficients;
    case DirectionalMode::Dominant: return kShL1Coefficients;
  }
  return 0;
}

namespace {

// h * reading(n) / reading(n0), per channel; h where the reading at n0 is not positive.
float rescaled(float h, float atShading, float atGeometric) {
  return atGeometric > 0.0f ? h * std::max(0.0f, atShading) / atGeometric : h;
}

// Luminance weights (Rec. 709), for the dominant direction.
constexpr Vec3 kLuminance(0.2126f, 0.7152f, 0.0722f);

}  // namespace

Rgb directionalIrradiance(DirectionalMode mode, const Rgb* c, Rgb h, Vec3 n0, Vec3 n) {
  Rgb out = h;
  switch (mode) {
    case DirectionalMode::None:
      break;
    case DirectionalMode::ShL1:
      for (int ch = 0; ch < 3; ++ch) {
        const Vec3 band1 = shBand1Vector(c[1][ch], c[2][ch], c[3][ch]);
        out[ch] = rescaled(h[ch], shL1DirectionalIrradiance(c[0][ch], band1, n),
                           shL1DirectionalIrradiance(c[0][ch], band1, n0));
      }
      break;
    case DirectionalMode::ShL2: {
      const Rgb at = shIrradiance(c, kShCoefficients, n), at0 = shIrradiance(c, kShCoefficients, n0);
      for (int ch = 0; ch < 3; ++ch) out[ch] = rescaled(h[ch], at[ch], at0[ch]);
      break;
    }
    case DirectionalMode::Dominant: {
      const float c0 = glm::dot(kLuminance, c[0]);
      const Vec3 band1 = shBand1Vector(glm::dot(kLuminance, c[1]), glm::dot(kLuminance, c[2]), glm::dot(kLuminance, c[3]));
      const float ratio = shL1DirectionalIrradiance(c0, band1, n), ratio0 = shL1DirectionalIrradiance(c0, band1, n0);
      for (int ch = 0; ch < 3; ++ch) out[ch] = rescaled(h[ch], ratio, ratio0);
      break;
    }
  }
  return out;
}

}  // namespace luxel
