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

namespace {

constexpr float kBand1Bound = 1.7320508f;  // max |Y1m / Y00| = sqrt 3
constexpr float kBand2Bound = 2.2360680f;  // max |Y2m / Y00| = sqrt 5 (Y20 at the pole)
float bound(int i) { return shBand(i) == 1 ? kBand1Bound : kBand2Bound; }

float ratio(float ci, float c0) { return c0 > 0.0f ? ci / c0 : 0.0f; }
float pack(float q, float b) { return std::clamp(0.5f + 0.5f * q / b, 0.0f, 1.0f); }
float unpack(float v, float b) { return (2.0f * v - 1.0f) * b; }

// The SH index of band-1 texture axis a (x, y, z) in the (y, z, x) order of the coefficients.
constexpr int kAxisCoefficient[3] = {3, 1, 2};

}  // namespace

int directionalTextureCount(DirectionalMode mode) {
  switch (mode) {
    case DirectionalMode::None: return 0;
    case DirectionalMode::ShL1: return 3;
    case DirectionalMode::ShL2: return 8;
    case DirectionalMode::Dominant: return 1;
  }
  return 0;
}

Rgb encodeDirectionalTexel(DirectionalMode mode, const Rgb* c, int k) {
  Rgb out(0.5f);
  switch (mode) {
    case DirectionalMode::None:
      break;
    case DirectionalMode::ShL1:
      for (int ch = 0; ch < 3; ++ch) out[ch] = pack(ratio(c[kAxisCoefficient[k]][ch], c[0][ch]), kBand1Bound);
      break;
    case DirectionalMode::ShL2:
      for (int ch = 0; ch < 3; ++ch) out[ch] = pack(ratio(c[k + 1][ch], c[0][ch]), bound(k + 1));
      break;
    case DirectionalMode::Dominant: {
      const float c0 = glm::dot(kLuminance, c[0]);
      for (int axis = 0; axis < 3; ++axis) out[axis] = pack(ratio(glm::dot(kLuminance, c[kAxisCoefficient[axis]]), c0), kBand1Bound);
      break;
    }
  }
  return out;
}

void decodeDirectionalTexel(DirectionalMode mode, const Rgb* values, Rgb* c) {
  const int count = directionalCoefficients(mode);
  for (int i = 0; i < count; ++i) c[i] = Rgb(i == 0 ? 1.0f : 0.0f);
  switch (mode) {
    case DirectionalMode::None:
      break;
    case DirectionalMode::ShL1:
      for (int axis = 0; axis < 3; ++axis)
        for (int ch = 0; ch < 3; ++ch) c[kAxisCoefficient[axis]][ch] = unpack(values[axis][ch], kBand1Bound);
      break;
    case DirectionalMode::ShL2:
      for (int i = 1; i < kShCoefficients; ++i)
        for (int ch = 0; ch < 3; ++ch) c[i][ch] = unpack(values[i - 1][ch], bound(i));
      break;
    case DirectionalMode::Dominant:
      for (int axis = 0; axis < 3; ++axis) c[kAxisCoefficient[axis]] = Rgb(unpack(values[0][axis], kBand1Bound));
      break;
  }
}

}  // namespace luxel
