// Spherical harmonics (core/spherical_harmonics.h) against closed forms: a constant, a clamped
// cosine, a single direction; rotation against evaluating the rotated function and against
// projecting it; the uniform hemisphere; the L1 directional reading; deringing.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/spherical_harmonics.h"

namespace {

using luxel::Rgb;
using luxel::Vec3;
constexpr float kPi = std::numbers::pi_v<float>;

// A Fibonacci lattice of n directions: each stands for 4 pi / n of solid angle. Smooth integrands
// integrate to about 1e-5 relative at n = 20,000 (band <= 4 products).
std::vector<Vec3> lattice(int n) {
  std::vector<Vec3> d(static_cast<size_t>(n));
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z);
    d[size_t(i)] = Vec3(float(r * std::cos(golden * i)), float(r * std::sin(golden * i)), float(z));
  }
  return d;
}

template <typename F>
std::array<double, 9> project(F&& radiance) {
  std::array<double, 9> c{};
  const auto dirs = lattice(20000);
  const double w = 4.0 * std::numbers::pi / double(dirs.size());
  for (const Vec3& d : dirs) {
    const double l = radiance(d);
    const auto y = luxel::shBasis(d);
    for (int i = 0; i < 9; ++i) c[size_t(i)] += w * l * y[size_t(i)];
  }
  return c;
}

TEST(SphericalHarmonics, ConstantProjectsToBandZeroAndGivesPiL) {
  const auto c = project([](Vec3) { return 2.0; });
  EXPECT_NEAR(c[0], 2.0 * std::sqrt(4.0 * std::numbers::pi), 1e-4);
  for (int i = 1; i < 9; ++i) EXPECT_NEAR(c[size_t(i)], 0.0, 1e-4) << i;
  float cf[9];
  for (int i = 0; i < 9; ++i) cf[i] = float(c[size_t(i)]);
  for (Vec3 n : {Vec3(0, 0, 1), glm::normalize(Vec3(1, -2, 0.5f))})
    EXPECT_NEAR(luxel::shIrradiance(cf, 9, n), 2.0f * kPi, 1e-3f);
}

TEST(SphericalHarmonics, ClampedCosineHasItsClosedFormCoefficients) {
  // L = max(0, z): c00 = pi Y00, c10 = 2 pi / 3 Y1, c20 = 2 pi * 0.315392 * (3/4 - 1/2).
  const auto c = project([](Vec3 d) { return std::max(0.0f, d.z); });
  EXPECT_NEAR(c[0], std::numbers::pi * 0.282095, 1e-4);
  EXPECT_NEAR(c[2], 2.0 * std::numbers::pi / 3.0 * 0.488603, 1e-4);
  EXPECT_NEAR(c[6], 2.0 * std::numbers::pi * 0.315392 * 0.25, 1e-4);
  for (int i : {1, 3, 4, 5, 7, 8}) EXPECT_NEAR(c[size_t(i)], 0.0, 1e-4) << i;
}

TEST(SphericalHarmonics, SingleDirectionReadsBackExactlyThroughTheL1Light) {
  const Vec3 d = glm::normalize(Vec3(0.3f, -0.2f, 0.9f));
  Rgb c[9] = {};
  luxel::shAddDirection(c, 9, d, Rgb(3.0f, 2.0f, 1.0f));
  const auto y = luxel::shBasis(d);
  for (int i = 0; i < 9; ++i) EXPECT_FLOAT_EQ(c[i].r, 3.0f * y[size_t(i)]);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int k = 0; k < 200; ++k) {
    const Vec3 n = glm::normalize(Vec3(u(rng), u(rng), u(rng)));
    const Vec3 band1 = luxel::shBand1Vector(c[1].r, c[2].r, c[3].r);
    // One distant light: E(n) = irradiance * max(0, n . d), which L1 read linearly misses.
    EXPECT_NEAR(luxel::shL1DirectionalIrradiance(c[0].r, band1, n), 3.0f * std::max(0.0f, glm::dot(n, d)), 1e-5f);
    EXPECT_NEAR(luxel::shIrradiance(c, 4, n).r, 3.0f * (0.25f + 0.5f * glm::dot(n, d)), 1e-5f);
  }
}

TEST(SphericalHarmonics, UniformHemisphereMatchesItsProjectionAndGivesItsIrradiance) {
  const Vec3 n = glm::normalize(Vec3(-0.4f, 0.8f, 0.2f));
  Rgb c[9] = {};
  luxel::shAddUniformHemisphere(c, 9, n, Rgb(1.5f));
  // 1.5 / pi over the hemisphere around n; the lattice's edge error at the hemisphere's rim is
  // about 1e-3 here.
  const auto p = project([&](Vec3 d) { return glm::dot(d, n) > 0.0f ? 1.5 / std::numbers::pi : 0.0; });
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(c[i].r, p[size_t(i)], 2e-3) << i;
  EXPECT_NEAR(luxel::shIrradiance(c, 4, n).r, 1.5f, 1e-5f);  // L1 is exact at the axis
}

TEST(SphericalHarmonics, RotationEqualsTheRotatedFunction) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int trial = 0; trial < 20; ++trial) {
    Rgb c[9], r[9];
    for (auto& v : c) v = Rgb(u(rng), u(rng), u(rng));
    const Vec3 axis = glm::normalize(Vec3(u(rng), u(rng), u(rng)));
    const glm::mat3 rot = glm::mat3(glm::rotate(glm::mat4(1.0f), 3.0f * u(rng), axis));
    for (int count : {4, 9}) {
      luxel::shRotate(c, count, rot, r);
      // f'(w) = f(R^T w) at random points, exactly (float rounding).
      for (int k = 0; k < 20; ++k) {
        const Vec3 w = glm::normalize(Vec3(u(rng), u(rng), u(rng)));
        const auto yw = luxel::shBasis(w), yb = luxel::shBasis(glm::transpose(rot) * w);
        float rotated = 0.0f, original = 0.0f;
        for (int i = 0; i < count; ++i) rotated += r[i].g * yw[size_t(i)], original += c[i].g * yb[size_t(i)];
        EXPECT_NEAR(rotated, original, 2e-5f * count);
      }
    }
    // Against projecting the rotated function by quadrature.
    const auto p = project([&](Vec3 w) {
      const auto y = luxel::shBasis(glm::transpose(rot) * w);
      double f = 0.0;
      for (int i = 0; i < 9; ++i) f += double(c[i].b) * y[size_t(i)];
      return f;
    });
    luxel::shRotate(c, 9, rot, r);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(r[i].b, p[size_t(i)], 1e-3) << i;
  }
}

TEST(SphericalHarmonics, WindowRemovesNegativeIrradianceAndKeepsSetsThatDoNotRing) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const auto probes = lattice(100000);
  int windowed = 0;
  for (int trial = 0; trial < 30; ++trial) {
    // A few lamps in random directions: the sharpest light SH can be asked to hold.
    Rgb c[9] = {};
    for (int k = 0; k < 1 + trial % 3; ++k)
      luxel::shAddDirection(c, 9, glm::normalize(Vec3(u(rng), u(rng), u(rng))), Rgb(1.0f + u(rng), 1.0f, 0.5f));
    for (int count : {4, 9}) {
      Rgb w[9];
      std::copy(c, c + 9, w);
      const float s = luxel::shNonNegativeWindow(w, count);
      ASSERT_GT(s, 0.0f);
      ASSERT_LE(s, 1.0f);
      windowed += s < 1.0f;
      luxel::shApplyWindow(w, count, s);
      const Rgb mean = kPi * luxel::kShY0 * w[0];
      for (const Vec3& n : probes) {
        const Rgb e = luxel::shIrradiance(w, count, n);
        ASSERT_GE(e.r, -1e-5f * mean.r);
        ASSERT_GE(e.g, -1e-5f * mean.g);
        ASSERT_GE(e.b, -1e-5f * mean.b);
      }
      // And the window is the largest that does so, within 2%: 2% less damping of band l > 0
      // brings some direction of some channel below the 0.5% margin.
      if (s < 0.98f) {
        Rgb wider[9];
        std::copy(c, c + 9, wider);
        luxel::shApplyWindow(wider, count, s * 1.02f);
        float lowest = INFINITY;
        for (const Vec3& n : probes) {
          const Rgb e = luxel::shIrradiance(wider, count, n);
          for (int ch = 0; ch < 3; ++ch) lowest = std::min(lowest, e[ch] / (kPi * luxel::kShY0 * c[0][ch]));
        }
        EXPECT_LT(lowest, 0.005f) << "trial " << trial << ", L" << (count == 4 ? 1 : 2) << ", window " << s;
      }
    }
  }
  EXPECT_GT(windowed, 30);  // single lamps always ring: the search had work to do
  Rgb hemi[9] = {};
  luxel::shAddUniformHemisphere(hemi, 9, Vec3(0, 0, 1), Rgb(1.0f));
  EXPECT_EQ(luxel::shNonNegativeWindow(hemi, 4), 1.0f);
}

}  // namespace

namespace {

TEST(SphericalHarmonics, SixteenFunctionsAreOrthonormalAndExtendTheNine) {
  const auto dirs = lattice(20000);
  const double w = 4.0 * std::numbers::pi / double(dirs.size());
  double gram[16][16] = {};
  for (const Vec3& d : dirs) {
    const auto y = luxel::shBasis16(d);
    const auto y9 = luxel::shBasis(d);
    for (int i = 0; i < 9; ++i) ASSERT_EQ(y[size_t(i)], y9[size_t(i)]);
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j) gram[i][j] += w * double(y[size_t(i)]) * double(y[size_t(j)]);
  }
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) EXPECT_NEAR(gram[i][j], i == j ? 1.0 : 0.0, 2e-4) << i << " " << j;
}

}  // namespace
