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

// A permutation of [0, l) chosen by p, evaluated at i: a hash restricted to the next power of two
// and cycle-walked down to l (Kensler, listing 3).
inline uint32_t permuteIndex(uint32_t i, uint32_t l, uint32_t p) {
  if (l <= 1) return 0;
  uint32_t w = l - 1;
  w |= w >> 1, w |= w >> 2, w |= w >> 4, w |= w >> 8, w |= w >> 16;
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
  } while (i >= l);
  return (i + p) % l;
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

// Sample s (< n) of n from pattern p (Kensler, listing 5, square aspect).
inline Vec2 multiJitter(uint32_t s, uint32_t n, uint32_t p) {
  uint32_t m = 1;
  while ((m + 1) * (m + 1) <= n) ++m;  // floor(sqrt(n)) columns
  const uint32_t rows = (n + m - 1) / m;
  s = permuteIndex(s, n, p * 0x51633e2du);
  const uint32_t sx = permuteIndex(s % m, m, p * 0x68bc21ebu);
  const uint32_t sy = permuteIndex(s / m, rows, p * 0x02e5be93u);
  const float jx = hashedUnitFloat(s, p * 0x967a889bu);
  const float jy = hashedUnitFloat(s, p * 0x368cc8b7u);
  const float x = (float(sx) + (float(sy) + jx) / float(rows)) / float(m);
  const float y = (float(s) + jy) / float(n);
  constexpr float kBelowOne = 0x1.fffffep-1f;
  return {x < kBelowOne ? x : kBelowOne, y < kBelowOne ? y : kBelowOne};
}

}  // namespace luxel
