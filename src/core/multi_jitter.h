// Correlated multi-jittered sampling: Kensler, "Correlated Multi-Jittered Sampling", Pixar
// Technical Memo 13-01, 2013. Sample s of N from pattern p is a point of [0,1)^2 such that the N
// points of one pattern are stratified in a near-square grid and in both 1-D projections, for any
// N (not only squares or powers of two). Different patterns (one per pixel and per use: the pixel
// footprint, a light's area, the gathered hemisphere) are independent, and each pattern visits its
// strata in its own order, so that the samples of two uses at the same index are not correlated.
#pragma once

#include <cstdint>

#include "luxel/scene.h"

namespace luxel {

// Remainders and quotients by a divisor fixed in advance, without a division (Lemire, Kaser and
// Kurz, "Faster Remainder by Direct Computation", 2019): exact for every 32-bit numerator. The
// sampler below divides by the same three counts for every sample, and hardware division was most
// of its cost (docs/performance.md, "Against a peer").
class FixedDivisor {
 public:
  explicit FixedDivisor(uint32_t d = 1) : d_(d), m_(~uint64_t(0) / d + 1) {}
  uint32_t divisor() const { return d_; }
  uint32_t remainder(uint32_t a) const {
    return uint32_t((static_cast<unsigned __int128>(m_ * a) * d_) >> 64);
  }
  uint32_t quotient(uint32_t a) const {
    return d_ == 1 ? a : uint32_t((static_cast<unsigned __int128>(m_) * a) >> 64);
  }

 private:
  uint32_t d_;
  uint64_t m_;
};

// A permutation of [0, l) chosen by p, evaluated at i: a hash restricted to the next power of two
// and cycle-walked down to l (Kensler, listing 3). `mask` is l - 1 with every bit below its
// highest set.
inline uint32_t permuteIndex(uint32_t i, const FixedDivisor& l, uint32_t mask, uint32_t p) {
  if (l.divisor() <= 1) return 0;
  const uint32_t w = mask;
  do {
    i ^= p;
    i *= 0xe170893du;
    i ^= p >> 16;
    i ^= (i & w) >> 4;
    i ^= p >> 8;
    i *= 0x0929eb3fu;
    i ^= p >> 23;
    i ^= (i & w) >> 1;
    i *= 1u | p >> 27;
    i *= 0x6935fa69u;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303u;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3u;
    i ^= (i & w) >> 2;
    i *= 0xc860a3dfu;
    i &= w;
    i ^= i >> 5;
  } while (i >= l.divisor());
  return l.remainder(i + p);
}

inline uint32_t maskBelow(uint32_t l) {
  uint32_t w = l > 0 ? l - 1 : 0;
  w |= w >> 1, w |= w >> 2, w |= w >> 4, w |= w >> 8, w |= w >> 16;
  return w;
}

inline uint32_t permuteIndex(uint32_t i, uint32_t l, uint32_t p) {
  return permuteIndex(i, FixedDivisor(l > 0 ? l : 1), maskBelow(l), p);
}

// A hashed float in [0, 1) (Kensler, listing 4).
inline float hashedUnitFloat(uint32_t i, uint32_t p) {
  i ^= p;
  i ^= i >> 17;
  i ^= i >> 10;
  i *= 0xb36534e5u;
  i ^= i >> 12;
  i ^= i >> 21;
  i *= 0x93fc4795u;
  i ^= 0xdf6e307fu;
  i ^= i >> 17;
  i *= 1u | p >> 18;
  return float(i >> 8) * 0x1p-24f;
}

// The n samples of any pattern (Kensler, listing 5, square aspect), with what depends on n alone
// worked out once: for loops that draw many patterns of the same count.
class MultiJitter {
 public:
  explicit MultiJitter(uint32_t n) {
    n = n > 0 ? n : 1;
    uint32_t m = 1;
    while ((m + 1) * (m + 1) <= n) ++m;  // floor(sqrt(n)) columns
    const uint32_t rows = (n + m - 1) / m;
    n_ = FixedDivisor(n), columns_ = FixedDivisor(m), rows_ = FixedDivisor(rows);
    nMask_ = maskBelow(n), columnMask_ = maskBelow(m), rowMask_ = maskBelow(rows);
    invColumns_ = 1.0f / float(m), invRows_ = 1.0f / float(rows), invN_ = 1.0f / float(n);
  }
  uint32_t count() const { return n_.divisor(); }

  // Sample s (< n) of pattern p.
  Vec2 operator()(uint32_t s, uint32_t p) const {
    s = permuteIndex(s, n_, nMask_, p * 0x51633e2du);
    const uint32_t sx = permuteIndex(columns_.remainder(s), columns_, columnMask_, p * 0x68bc21ebu);
    const uint32_t sy = permuteIndex(columns_.quotient(s), rows_, rowMask_, p * 0x02e5be93u);
    const float jx = hashedUnitFloat(s, p * 0x967a889bu);
    const float jy = hashedUnitFloat(s, p * 0x368cc8b7u);
    const float x = (float(sx) + (float(sy) + jx) * invRows_) * invColumns_;
    const float y = (float(s) + jy) * invN_;
    constexpr float kBelowOne = 0x1.fffffep-1f;
    return {x < kBelowOne ? x : kBelowOne, y < kBelowOne ? y : kBelowOne};
  }

 private:
  FixedDivisor n_, columns_, rows_;
  uint32_t nMask_ = 0, columnMask_ = 0, rowMask_ = 0;
  float invColumns_ = 1.0f, invRows_ = 1.0f, invN_ = 1.0f;
};

// Sample s (< n) of n from pattern p.
inline Vec2 multiJitter(uint32_t s, uint32_t n, uint32_t p) { return MultiJitter(n)(s, p); }

}  // namespace luxel
