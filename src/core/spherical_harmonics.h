// Real spherical harmonics to band 2 (nine functions) and the irradiance they give a surface of any
// normal: Ramamoorthi and Hanrahan, "An Efficient Representation for Irradiance Environment
// Maps", SIGGRAPH 2001 (equations 3 and 8-9). Light from all around a point, summed as nine
// numbers, gives the irradiance for every normal to within a few percent, where a sum of
// irradiance vectors loses whatever arrives from opposite sides.
//
// Coefficients are projections of incident radiance, c_i = integral of L(w) Y_i(w) over the
// sphere (the convention of three.js's SphericalHarmonics3 and of Sloan's "Stupid Spherical
// Harmonics (SH) Tricks", GDC 2008), in world space. L1 uses the first 4, L2 all 9.
#pragma once

#include <array>
#include <numbers>

#include "luxel/scene.h"

namespace luxel {

inline constexpr int kShCoefficients = 9;
inline constexpr int kShL1Coefficients = 4;

// The band-0 and band-1 constants: Y00 = kShY0, Y1m = kShY1 * (y, z, x).
inline constexpr float kShY0 = 0.282095f;
inline constexpr float kShY1 = 0.488603f;

// The nine functions at unit direction d, in the order (l, m) = (0,0), (1,-1), (1,0), (1,1),
// (2,-2), (2,-1), (2,0), (2,1), (2,2).
inline std::array<float, kShCoefficients> shBasis(Vec3 d) {
  return {kShY0,
          kShY1 * d.y,
          kShY1 * d.z,
          kShY1 * d.x,
          1.092548f * d.x * d.y,
          1.092548f * d.y * d.z,
          0.315392f * (3.0f * d.z * d.z - 1.0f),
          1.092548f * d.x * d.z,
          0.546274f * (d.x * d.x - d.y * d.y)};
}

// Band 3 as well (sixteen functions, seed 004's default of four bands): the nine of shBasis, then
// (3,-3) ... (3,3), in the same convention (no Condon-Shortley sign, as band 1's y, z, x).
inline constexpr int kShBand3Coefficients = 16;
inline std::array<float, kShBand3Coefficients> shBasis16(Vec3 d) {
  const auto low = shBasis(d);
  const float x = d.x, y = d.y, z = d.z;
  return {low[0], low[1], low[2], low[3], low[4], low[5], low[6], low[7], low[8],
          0.590044f * y * (3.0f * x * x - y * y),
          2.890611f * x * y * z,
          0.457046f * y * (5.0f * z * z - 1.0f),
          0.373176f * z * (5.0f * z * z - 3.0f),
          0.457046f * x * (5.0f * z * z - 1.0f),
          1.445306f * z * (x * x - y * y),
          0.590044f * x * (x * x - 3.0f * y * y)};
}

// The clamped cosine's band weights (pi, 2 pi / 3, pi / 4) per coefficient: irradiance for normal
// n is sum_i kShCosine[i] * radiance[i] * shBasis(n)[i].
inline constexpr std::array<float, kShCoefficients> kShCosine = {
    std::numbers::pi_v<float>,        2.0f * std::numbers::pi_v<float> / 3.0f, 2.0f * std::numbers::pi_v<float> / 3.0f,
    2.0f * std::numbers::pi_v<float> / 3.0f, std::numbers::pi_v<float> / 4.0f,        std::numbers::pi_v<float> / 4.0f,
    std::numbers::pi_v<float> / 4.0f,        std::numbers::pi_v<float> / 4.0f,        std::numbers::pi_v<float> / 4.0f};

// The band of coefficient i (0, 1 or 2).
inline constexpr int shBand(int i) { return i == 0 ? 0 : i < 4 ? 1 : 2; }

// Adds the projection of a delta of radiance integral `weight` (W m^-2 sr^0: radiance times
// solid angle) arriving from unit direction d: c_i += weight * Y_i(d), for the first `count`.
template <typename T>
void shAddDirection(T* c, int count, Vec3 d, const T& weight) {
  const std::array<float, kShCoefficients> y = shBasis(d);
  for (int i = 0; i < count; ++i) c[i] += weight * y[size_t(i)];
}

// Irradiance at unit normal n from `count` (4 or 9) coefficients, evaluated linearly
// (Ramamoorthi and Hanrahan's convolution with the clamped cosine). It rings: a strongly
// directional L1 set goes negative facing away from the light (see shL1DirectionalIrradiance and
// shNonNegativeWindow).
template <typename T>
T shIrradiance(const T* c, int count, Vec3 n) {
  const std::array<float, kShCoefficients> y = shBasis(n);
  T e = c[0] * (kShCosine[0] * y[0]);
  for (int i = 1; i < count; ++i) e += c[i] * (kShCosine[size_t(i)] * y[size_t(i)]);
  return e;
}

// The band-1 vector of a set, (c3, c1, c2) / kShY1: the integral of L(w) w, in x, y, z.
inline Vec3 shBand1Vector(float c1, float c2, float c3) { return Vec3(c3, c1, c2) / kShY1; }

// L1 read as a constant plus one directional light (Sloan 2008, "extracting a directional light"):
// with m0 = c0 / Y00 (the integral of L) and m1 the band-1 vector, a light of irradiance |m1| along
// m1 / |m1| and a uniform radiance (m0 - |m1|) / 4pi give the same four coefficients, and the
// irradiance
//   E(n) = (m0 - |m1|) / 4 + |m1| max(0, n . m1 / |m1|),
// which is exact for one distant light, never negative (|m1| <= m0 for any L >= 0; clamped when
// rounding breaks it) and has no ring. One channel.
float shL1DirectionalIrradiance(float c0, Vec3 band1, Vec3 n);

// Coefficients of the rotated function f'(w) = f(R^T w), for `count` 4 or 9 (R a rotation):
// band 1 turns as a vector, band 2 through five fixed directions (the band is closed under
// rotation, so five samples of it determine it).
void shRotate(const Rgb* in, int count, const glm::mat3& rotation, Rgb* out);

// The incident radiance of a uniform hemisphere around unit n that gives irradiance `e` at n
// (radiance e / pi over the hemisphere), projected: c_i += ... for the first `count`.
void shAddUniformHemisphere(Rgb* c, int count, Vec3 n, Rgb e);

// Deringing for linear evaluation (shIrradiance): the largest s in [0, 1] such that, with band l
// scaled by s^l, the irradiance is >= 0 for every normal, per channel of one set (the smallest of
// the three). L1 in closed form. L2: along each direction the irradiance is a quadratic in s, so
// 160 directions bound s from above in closed form; the minimum of the irradiance over the sphere
// (a quadratic polynomial there), found by descent from the best of them, cuts it again where it
// falls below a margin of 0.5% of the mean irradiance (tested against 100,000 directions, and s
// within 2% of the largest). 1 when the set already does not ring; 0 when c0 <= 0.
float shNonNegativeWindow(const Rgb* c, int count);
// Scales band l of `c` by s^l.
void shApplyWindow(Rgb* c, int count, float s);

}  // namespace luxel
