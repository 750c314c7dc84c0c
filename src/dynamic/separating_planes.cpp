#include "dynamic/separating_planes.h"

#include <algorithm>
#include <limits>

namespace luxel {
namespace {

// A polygon's prism: its corners, then the same lifted.
int prismCorners(const Polygon& p, Vec3 lift, std::array<Vec3, 8>& out) {
  for (int i = 0; i < p.count; ++i) out[size_t(i)] = p.v[size_t(i)], out[size_t(i + p.count)] = p.v[size_t(i)] + lift;
  return 2 * p.count;
}

}  // namespace

SeparatingPlanes::SeparatingPlanes(const Polygon& source, Vec3 lift, const std::array<Vec3, 8>& box, float tolerance)
    : tolerance_(tolerance) {
  std::array<Vec3, 8> prism;
  const int n = prismCorners(source, lift, prism);
  // The plane through a, b and c, oriented with the prism below it, kept when it has the prism
  // below and the box above (each within the tolerance).
  auto consider = [&](Vec3 a, Vec3 b, Vec3 c) {
    Vec3 normal = glm::cross(b - a, c - a);
    const float length = glm::length(normal);
    if (!(length > 0.0f)) return;
    normal /= length;
    const float w = glm::dot(normal, a);
    float low = std::numeric_limits<float>::max(), high = -low;
    for (int i = 0; i < n; ++i) {
      const float x = glm::dot(normal, prism[size_t(i)]) - w;
      low = std::min(low, x), high = std::max(high, x);
    }
    if (high > tolerance_) {
      if (low < -tolerance_) return;  // the plane cuts the prism
      normal = -normal;               // the prism above: turn the plane over
    }
    const float side = glm::dot(normal, a);
    for (const Vec3& k : box)
      if (glm::dot(normal, k) - side < -tolerance_) return;
    planes_.emplace_back(normal, side);
  };
  // Edges of the prism along the polygon, at both heights, with each corner of the box.
  for (int level = 0; level < 2; ++level)
    for (int i = 0; i < source.count; ++i) {
      const Vec3 a = prism[size_t(level * source.count + i)], b = prism[size_t(level * source.count + (i + 1) % source.count)];
      for (const Vec3& k : box) consider(a, b, k);
    }
  // Edges of the box with each corner of the prism.
  for (int i = 0; i < 8; ++i)
    for (int bit = 1; bit < 8; bit <<= 1)
      if (!(i & bit))
        for (int j = 0; j < n; ++j) consider(box[size_t(i)], box[size_t(i | bit)], prism[size_t(j)]);
}

bool SeparatingPlanes::separates(const Polygon& receiver, Vec3 lift) const {
  std::array<Vec3, 8> prism;
  const int n = prismCorners(receiver, lift, prism);
  for (const glm::vec4& q : planes_) {
    const Vec3 normal(q);
    bool below = true;
    for (int i = 0; i < n && below; ++i) below = glm::dot(normal, prism[size_t(i)]) <= q.w + tolerance_;
    if (below) return true;
  }
  return false;
}

}  // namespace luxel
