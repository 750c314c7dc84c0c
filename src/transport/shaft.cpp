#include "transport/shaft.h"

#include <algorithm>

namespace luxel {

Shaft::Shaft(const Polygon& a, const Polygon& b, float tolerance) : tolerance_(tolerance) {
  for (const Polygon* p : {&a, &b})
    for (int i = 0; i < p->count; ++i) points_.push_back(p->v[i]);
  lo_ = hi_ = points_[0];
  for (const Vec3& p : points_) lo_ = glm::min(lo_, p), hi_ = glm::max(hi_, p);
  const float scale = glm::length(hi_ - lo_);
  if (!(scale > 0.0f)) return;
  // At most 8 corners: every triple whose plane has all corners on one side is a hull face.
  // Brute force (56 triples) beats a general hull algorithm at this size.
  const size_t n = points_.size();
  const float flat = 1e-6f * scale;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      for (size_t k = j + 1; k < n; ++k) {
        Vec3 normal = glm::cross(points_[j] - points_[i], points_[k] - points_[i]);
        float len = glm::length(normal);
        if (!(len > 1e-12f * scale * scale)) continue;
        normal /= len;
        float w = -glm::dot(normal, points_[i]);
        bool above = false, below = false;
        for (const Vec3& p : points_) {
          float d = glm::dot(normal, p) + w;
          above |= d > flat;
          below |= d < -flat;
        }
        if (above && below) continue;
        if (!above && !below) {  // every corner in one plane: a flat hull encloses nothing
          planes_.clear();
          return;
        }
        if (above) normal = -normal, w = -w;  // outward: the other corners lie behind
        planes_.emplace_back(normal, w);
      }
}

bool Shaft::mayIntersect(const Polygon& poly) const {
  if (planes_.empty()) return true;
  // Separated by a hull plane: every corner of the polygon outside it.
  for (const glm::vec4& pl : planes_) {
    const Vec3 n(pl);
    bool outside = true;
    for (int i = 0; i < poly.count && outside; ++i) outside = glm::dot(n, poly.v[i]) + pl.w >= -tolerance_;
    if (outside) return false;
  }
  // Separated by the polygon's own plane: the whole hull on one side of it.
  const Vec3 n = poly.normal();
  const float w = -glm::dot(n, poly.v[0]);
  bool above = false, below = false;
  for (const Vec3& p : points_) {
    float d = glm::dot(n, p) + w;
    above |= d > tolerance_;
    below |= d < -tolerance_;
  }
  return above && below;
}

}  // namespace luxel
