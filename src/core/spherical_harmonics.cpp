// Spherical-harmonic helpers: see core/spherical_harmonics.h.
#include "core/spherical_harmonics.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

namespace luxel {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// Five directions whose band-2 values form an invertible 5 x 5 matrix, and its inverse.
struct Band2Frame {
  std::array<Vec3, 5> directions;
  Eigen::Matrix<float, 5, 5> inverse;
  Band2Frame() {
    const float s = 1.0f / std::sqrt(2.0f);
    directions = {Vec3(1, 0, 0), Vec3(0, 0, 1), Vec3(s, s, 0), Vec3(s, 0, s), Vec3(0, s, s)};
    Eigen::Matrix<float, 5, 5> m;
    for (int i = 0; i < 5; ++i) {
      const auto y = shBasis(directions[size_t(i)]);
      for (int j = 0; j < 5; ++j) m(i, j) = y[size_t(4 + j)];
    }
    inverse = m.inverse();
  }
};

const Band2Frame& band2Frame() {
  static const Band2Frame frame;
  return frame;
}

// Unit directions spread evenly over the sphere (a Fibonacci lattice): starting points for the
// deringing search. Kept as columns of their coordinates and products, so that a quadratic's
// values at all of them are a loop the compiler vectorises.
constexpr int kLatticeSize = 160;  // a multiple of the vector width
struct SphereLattice {
  std::array<Vec3, kLatticeSize> d;
  // x, y, z, then x^2, y^2, z^2, 2xy, 2yz, 2xz.
  std::array<std::array<float, kLatticeSize>, 9> column;
  SphereLattice() {
    const float golden = kPi * (3.0f - std::sqrt(5.0f));
    for (int i = 0; i < kLatticeSize; ++i) {
      const float z = 1.0f - (2.0f * float(i) + 1.0f) / float(kLatticeSize);
      const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
      const Vec3 v(r * std::cos(golden * float(i)), r * std::sin(golden * float(i)), z);
      d[size_t(i)] = v;
      const float c[9] = {v.x, v.y, v.z, v.x * v.x, v.y * v.y, v.z * v.z, 2 * v.x * v.y, 2 * v.y * v.z, 2 * v.x * v.z};
      for (int k = 0; k < 9; ++k) column[size_t(k)][size_t(i)] = c[k];
    }
  }
};

const SphereLattice& sphereLattice() {
  static const SphereLattice lattice;
  return lattice;
}

// The linear irradiance of one channel of L2 on the unit sphere as a polynomial,
// E(n) = a + b . n + n^T Q n (band 2 is a quadratic form there: 3z^2 - 1 = 2z^2 - x^2 - y^2).
struct Quadratic {
  float a;
  Vec3 b;
  glm::mat3 q;
  float at(Vec3 n) const { return a + glm::dot(b, n) + glm::dot(n, q * n); }
};

Quadratic irradiancePolynomial(const float* c, int count, float s) {
  Quadratic p;
  p.a = kShCosine[0] * kShY0 * c[0];
  p.b = (kShCosine[1] * kShY1 * s) * Vec3(c[3], c[1], c[2]);
  p.q = glm::mat3(0.0f);
  if (count >= kShCoefficients) {
    const float w = kShCosine[4] * s * s;
    glm::mat3& m = p.q;
    auto sym = [&](int i, int j, float v) { m[i][j] += v, m[j][i] += v; };
    sym(0, 1, 0.5f * 1.092548f * c[4] * w);  // xy
    sym(1, 2, 0.5f * 1.092548f * c[5] * w);  // yz
    const float k20 = 0.315392f * c[6] * w;  // 2z^2 - x^2 - y^2
    m[2][2] += 2.0f * k20, m[0][0] -= k20, m[1][1] -= k20;
    sym(0, 2, 0.5f * 1.092548f * c[7] * w);  // xz
    const float k22 = 0.546274f * c[8] * w;  // x^2 - y^2
    m[0][0] += k22, m[1][1] -= k22;
  }
  return p;
}

// Along lattice direction i the windowed irradiance is a quadratic in the scale s:
// E_s(d_i) = a + s beta_i + s^2 gamma_i, with beta_i = b . d_i and gamma_i = d_i^T Q d_i.
struct LatticeTerms {
  std::array<float, kLatticeSize> beta, gamma;
  explicit LatticeTerms(const Quadratic& p) {
    const SphereLattice& l = sphereLattice();
    const float q[6] = {p.q[0][0], p.q[1][1], p.q[2][2], p.q[0][1], p.q[1][2], p.q[0][2]};
    for (int i = 0; i < kLatticeSize; ++i) {
      beta[size_t(i)] = p.b.x * l.column[0][size_t(i)] + p.b.y * l.column[1][size_t(i)] + p.b.z * l.column[2][size_t(i)];
      gamma[size_t(i)] = q[0] * l.column[3][size_t(i)] + q[1] * l.column[4][size_t(i)] + q[2] * l.column[5][size_t(i)] +
                         q[3] * l.column[6][size_t(i)] + q[4] * l.column[7][size_t(i)] + q[5] * l.column[8][size_t(i)];
    }
  }
};

// The smallest irradiance of one channel on the sphere at scale s (`whole` is its polynomial at
// s = 1, `terms` its lattice terms), and where: the best of the lattice, then projected gradient
// descent on the sphere from it (a quadratic on the sphere has few, wide basins: the lattice's
// spacing of 0.28 rad starts in the deepest).
float minimumIrradiance(const Quadratic& whole, const LatticeTerms& terms, float s, Vec3& where) {
  std::array<float, kLatticeSize> e;
  for (int i = 0; i < kLatticeSize; ++i) e[size_t(i)] = whole.a + s * terms.beta[size_t(i)] + (s * s) * terms.gamma[size_t(i)];
  // The lowest in four independent chains, then where it is.
  float m[4] = {e[0], e[1], e[2], e[3]};
  for (int i = 4; i < kLatticeSize; i += 4)
    for (int k = 0; k < 4; ++k) m[k] = std::min(m[k], e[size_t(i + k)]);
  float lowest = std::min(std::min(m[0], m[1]), std::min(m[2], m[3]));
  const size_t first = size_t(std::find(e.begin(), e.end(), lowest) - e.begin());
  Vec3 best = sphereLattice().d[std::min(first, size_t(kLatticeSize - 1))];  // NaN: any
  Quadratic p = whole;
  p.b *= s, p.q *= s * s;
  // Step below the inverse of the gradient's Lipschitz bound.
  float qNorm = 0.0f;
  for (int i = 0; i < 3; ++i) qNorm += glm::length(p.q[i]);
  const float step = 0.5f / (glm::length(p.b) + 2.0f * qNorm + 1e-30f);
  for (int it = 0; it < 40; ++it) {
    const Vec3 g = p.b + 2.0f * (p.q * best);
    const Vec3 tangent = g - glm::dot(g, best) * best;
    const Vec3 next = glm::normalize(best - step * tangent);
    const float value = p.at(next);
    // Steps that gain under 1e-5 of the mean irradiance end it: the margin is 500 times that.
    if (!(value < lowest - 1e-5f * whole.a)) break;
    lowest = value, best = next;
  }
  where = best;
  return lowest;
}

// The first root past 0 of a + s beta + s^2 gamma (a > 0), or 1 if there is none in (0, 1].
float firstRoot(double a, double beta, double gamma) {
  double root = INFINITY;
  if (std::abs(gamma) <= 1e-12 * (std::abs(a) + std::abs(beta))) {
    if (beta < 0.0) root = -a / beta;
  } else {
    const double disc = beta * beta - 4.0 * gamma * a;
    if (disc >= 0.0) {
      // The stable pair of roots, q / gamma and a / q.
      const double q = -0.5 * (beta + std::copysign(std::sqrt(disc), beta));
      for (double r : {q / gamma, q != 0.0 ? a / q : INFINITY})
        if (r > 0.0) root = std::min(root, r);
    }
  }
  return float(std::min(root, 1.0));
}

float channelWindow(const float* c, int count) {
  if (!(c[0] > 0.0f)) return 0.0f;
  if (count <= kShL1Coefficients) {
    // E(n) = m0 / 4 + s |m1| / 2 cos: non-negative when s |m1| <= m0 / 2.
    const float m0 = c[0] / kShY0, m1 = glm::length(shBand1Vector(c[1], c[2], c[3]));
    return m1 > 0.5f * m0 ? 0.5f * m0 / m1 : 1.0f;
  }
  const float margin = 0.005f * kPi * kShY0 * c[0];  // 0.5% of the mean irradiance, pi m0 / 4pi
  const Quadratic whole = irradiancePolynomial(c, count, 1.0f);
  const LatticeTerms terms(whole);
  const float a = whole.a - margin;
  // Each lattice direction bounds the window from above in closed form: where its quadratic in s
  // reaches the margin, if it does by s = 1 (below it at 1, or dipping below it on the way).
  float s = 1.0f;
  for (int i = 0; i < kLatticeSize; ++i) {
    const float beta = terms.beta[size_t(i)], gamma = terms.gamma[size_t(i)];
    const bool dips = gamma > 0.0f && beta < 0.0f && -beta < 2.0f * gamma && beta * beta > 4.0f * gamma * a;
    if (a + beta + gamma < 0.0f || dips) s = std::min(s, firstRoot(a, beta, gamma));
  }
  // The descent then looks between the directions, and each one it finds below the margin cuts
  // the window again (a cutting-plane search: one or two rounds, where bisecting on s took
  // twenty descents). Each cut goes just inside its root, so that the next check is not lost to
  // rounding.
  if (s < 1.0f) s *= 1.0f - 1e-4f;
  for (int round = 0; round < 8; ++round) {
    Vec3 where;
    if (minimumIrradiance(whole, terms, s, where) >= margin) return s;
    s = std::min(s, firstRoot(a, glm::dot(whole.b, where), glm::dot(where, whole.q * where))) * (1.0f - 1e-4f);
  }
  // Rounds that keep finding new directions (not seen in testing): bisect below s.
  float lo = 0.0f, hi = s;  // lo always passes: only band 0 left
  for (int it = 0; it < 20; ++it) {
    const float mid = 0.5f * (lo + hi);
    Vec3 where;
    (minimumIrradiance(whole, terms, mid, where) >= margin ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

float shL1DirectionalIrradiance(float c0, Vec3 band1, Vec3 n) {
  const float m0 = std::max(0.0f, c0 / kShY0);
  const float length = std::min(glm::length(band1), m0);
  if (!(length > 0.0f)) return 0.25f * m0;
  return 0.25f * (m0 - length) + std::max(0.0f, glm::dot(n, band1)) * (length / glm::length(band1));
}

void shRotate(const Rgb* in, int count, const glm::mat3& rotation, Rgb* out) {
  out[0] = in[0];
  if (count < kShL1Coefficients) return;
  // Band 1: coefficient vector (c3, c1, c2) turns with the function.
  for (int ch = 0; ch < 3; ++ch) {
    const Vec3 v = rotation * Vec3(in[3][ch], in[1][ch], in[2][ch]);
    out[1][ch] = v.y, out[2][ch] = v.z, out[3][ch] = v.x;
  }
  if (count < kShCoefficients) return;
  // Band 2: f'(d_i) = f(R^T d_i) at the five frame directions, then back to coefficients.
  const Band2Frame& frame = band2Frame();
  const glm::mat3 back = glm::transpose(rotation);
  Eigen::Matrix<float, 5, 5> values;  // [direction][input coefficient]
  for (int i = 0; i < 5; ++i) {
    const auto y = shBasis(back * frame.directions[size_t(i)]);
    for (int j = 0; j < 5; ++j) values(i, j) = y[size_t(4 + j)];
  }
  const Eigen::Matrix<float, 5, 5> m = frame.inverse * values;
  for (int ch = 0; ch < 3; ++ch)
    for (int i = 0; i < 5; ++i) {
      float sum = 0.0f;
      for (int j = 0; j < 5; ++j) sum += m(i, j) * in[4 + j][ch];
      out[4 + i][ch] = sum;
    }
}

void shAddUniformHemisphere(Rgb* c, int count, Vec3 n, Rgb e) {
  // Radiance L = e / pi over the hemisphere: integral of L = 2 pi L = 2 e, integral of L w = pi L n
  // = e n; band 2: integral of Y20 over the hemisphere about its axis is 0 (P2 integrates to 0
  // over [0, 1]), and the other band-2 functions are odd about the axis, so band 2 gets nothing.
  c[0] += (2.0f * kShY0) * e;
  if (count >= kShL1Coefficients) {
    c[1] += (kShY1 * n.y) * e;
    c[2] += (kShY1 * n.z) * e;
    c[3] += (kShY1 * n.x) * e;
  }
}

float shNonNegativeWindow(const Rgb* c, int count) {
  float s = 1.0f;
  for (int ch = 0; ch < 3; ++ch) {
    float channel[kShCoefficients] = {};
    for (int i = 0; i < count; ++i) channel[i] = c[i][ch];
    s = std::min(s, channelWindow(channel, count));
  }
  return s;
}

void shApplyWindow(Rgb* c, int count, float s) {
  for (int i = 1; i < count; ++i) c[i] *= std::pow(s, float(shBand(i)));
}

}  // namespace luxel
