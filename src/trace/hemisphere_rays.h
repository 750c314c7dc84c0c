// Stratified directions over an element's hemisphere, jittered deterministically per element: the
// validity test of lightmap texels, the transfer bake's visibility and the gathered SH directions
// all draw theirs here, so that the same element gets the same directions every run.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>

#include "luxel/scene.h"

namespace luxel {

// A frame about unit `n` and the two hemisphere warps every gatherer here uses.
struct HemisphereFrame {
  explicit HemisphereFrame(Vec3 normal) : n(normal) {
    const Vec3 a = std::abs(n.x) > 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
    t = glm::normalize(glm::cross(a, n));
    b = glm::cross(n, t);
  }
  // Cosine-weighted (pdf cos / pi) from a point of [0,1)^2: for irradiance, and for visibility as
  // the cosine sees it.
  Vec3 cosine(float u1, float u2) const {
    const float r = std::sqrt(u1), phi = 2.0f * std::numbers::pi_v<float> * u2;
    return r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0f, 1.0f - u1)) * n;
  }
  // Uniform over the hemisphere (pdf 1 / 2 pi): cos theta uniform in [0, 1].
  Vec3 uniform(float z, float u2) const {
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * std::numbers::pi_v<float> * u2;
    return s * std::cos(phi) * t + s * std::sin(phi) * b + z * n;
  }
  Vec3 n, t, b;
};

// `side` x `side` strata over the hemisphere about unit `n`: stratum (i, j) of one element. The
// jitter is an xorshift stream seeded by the element's index and a salt (one per use).
class HemisphereStrata {
 public:
  HemisphereStrata(Vec3 n, int side, size_t element, uint32_t salt) : frame_(n), side_(side) {
    state_ = uint32_t(element) * 2654435761u + salt;
  }

  Vec3 cosine(int i, int j) {
    const auto [u1, u2] = jittered(i, j);
    return frame_.cosine(u1, u2);
  }
  Vec3 uniform(int i, int j) {
    const auto [z, u2] = jittered(i, j);
    return frame_.uniform(z, u2);
  }
  // Every stratum's direction, cosine-weighted or uniform, stratum (i, j) at out[j * side + i]
  // (out holds side * side).
  enum class Warp { Cosine, Uniform };
  void directions(Warp warp, std::span<Vec3> out) {
    for (int j = 0; j < side_; ++j)
      for (int i = 0; i < side_; ++i) out[size_t(j * side_ + i)] = warp == Warp::Cosine ? cosine(i, j) : uniform(i, j);
  }

 private:
  float next() {
    state_ ^= state_ << 13, state_ ^= state_ >> 17, state_ ^= state_ << 5;
    return float(state_ & 0xFFFFFF) / float(0x1000000);
  }
  std::pair<float, float> jittered(int i, int j) {
    const float u1 = (float(i) + next()) / float(side_);
    const float u2 = (float(j) + next()) / float(side_);
    return {u1, u2};
  }
  HemisphereFrame frame_;
  int side_;
  uint32_t state_;
};

// The side of the square number of strata at most `rays` (at least 1).
inline int strataSide(int rays) { return std::max(1, int(std::sqrt(double(std::max(rays, 1))))); }

}  // namespace luxel
