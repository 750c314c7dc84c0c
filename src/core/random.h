// Small, fast, stateless random numbers. Samples are derived from (seed, index) so that the same
// form factor computed by a row (gather) or by a column (shooting) draws the same samples.
#pragma once

#include <cstdint>

namespace luxel {

// PCG-style 32-bit hash (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient
// Statistically Good Algorithms for Random Number Generation"; the RXS-M-XS output function).
inline uint32_t pcgHash(uint32_t v) {
  uint32_t state = v * 747796405u + 2891336453u;
  uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

inline uint32_t hashCombine(uint32_t a, uint32_t b) { return pcgHash(a ^ (b * 0x9E3779B9u + 0x7F4A7C15u)); }

// A sequence of uniform floats in [0,1) from a seed.
class Rng {
 public:
  explicit Rng(uint32_t seed) : state_(pcgHash(seed)) {}
  uint32_t nextUint() {
    state_ = state_ * 747796405u + 2891336453u;
    uint32_t word = ((state_ >> ((state_ >> 28u) + 4u)) ^ state_) * 277803737u;
    return (word >> 22u) ^ word;
  }
  float next() { return float(nextUint() >> 8) * 0x1p-24f; }

 private:
  uint32_t state_;
};

}  // namespace luxel
