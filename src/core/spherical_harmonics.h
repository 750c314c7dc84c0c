// Real spherical harmonics to band 2 (nine functions) and the irradiance they give a surface of any
// normal: Ramamoorthi and Hanrahan, "An Efficient Representation for Irradiance Environment
// Maps", SIGGRAPH 2001 (equations 3 and 8-9). Light from all around a point, summed as nine
// numbers, gives the irradiance for every normal to within a few percent, where a sum of
// irradiance vectors loses whatever arrives from opposite sides.
#pragma once

#include <array>
#include <numbers>

#include "luxel/scene.h"

namespace luxel {

inline constexpr int kShCoefficients = 9;

// The nine functions at unit direction d, in the order (l, m) = (0,0), (1,-1), (1,0), (1,1),
// (2,-2), (2,-1), (2,0), (2,1), (2,2).
inline std::array<float, kShCoefficients> shBasis(Vec3 d) {
  return {0.282095f,
          0.488603f * d.y,
          0.488603f * d.z,
          0.488603f * d.x,
          1.092548f * d.x * d.y,
          1.092548f * d.y * d.z,
          0.315392f * (3.0f * d.z * d.z - 1.0f),
          1.092548f * d.x * d.z,
          0.546274f * (d.x * d.x - d.y * d.y)};
}

// The clamped cosine's band weights (pi, 2 pi / 3, pi / 4) per coefficient: irradiance for normal
// n is sum_i kShCosine[i] * radiance[i] * shBasis(n)[i].
inline constexpr std::array<float, kShCoefficients> kShCosine = {
    std::numbers::pi_v<float>,        2.0f * std::numbers::pi_v<float> / 3.0f, 2.0f * std::numbers::pi_v<float> / 3.0f,
    2.0f * std::numbers::pi_v<float> / 3.0f, std::numbers::pi_v<float> / 4.0f,        std::numbers::pi_v<float> / 4.0f,
    std::numbers::pi_v<float> / 4.0f,        std::numbers::pi_v<float> / 4.0f,        std::numbers::pi_v<float> / 4.0f};

}  // namespace luxel
