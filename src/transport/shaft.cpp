#include "transport/shaft.h"

#include <algorithm>
#include <span>

#include "trace/ray_tracer.h"

namespace luxel {

Shaft::Shaft(const Polygon& a, const Polygon& b, float tolerance) : tolerance_(tolerance) {
  for (const Polygon* p : {&a, &b})
    for (int i = 0; i < p->count; ++i) points_[pointCount_++] = p->v[i];
  const std::span<const Vec3> points(points_.data(), size_t(pointCount_));
  lo_ = hi_ = points[0];
  for (const Vec3& p : points) lo_ = glm::min(lo_, p), hi_ = glm::max(hi_, p);
  const float scale = glm::length(hi_ - lo_);
  if (!(scale > 0.0f)) return;
  // A face of the hull of two convex polygons is one polygon's own plane, or a plane through an
  // edge of one polygon and a corner of the other (two corners of one polygon on a hull face are
  // the ends of one of its edges). Those are the candidates; each is kept when every corner lies
  // on one side of it.
  const float flat = 1e-6f * scale;
  auto consider = [&](Vec3 p0, Vec3 p1, Vec3 p2) {
    Vec3 normal = glm::cross(p1 - p0, p2 - p0);
    const float len = glm::length(normal);
    if (!(len > 1e-12f * scale * scale)) return true;
    normal /= len;
    float w = -glm::dot(normal, p0);
    bool above = false, below = false;
    for (const Vec3& p : points) {
      const float d = glm::dot(normal, p) + w;
      above |= d > flat;
      below |= d < -flat;
    }
    if (above && below) return true;
    if (!above && !below) return false;      // every corner in one plane: a flat hull encloses nothing
    if (above) normal = -normal, w = -w;     // outward: the other corners lie behind
    planes_[size_t(planeCount_++)] = glm::vec4(normal, w);
    return true;
  };
  const Polygon* polys[2] = {&a, &b};
  for (int side = 0; side < 2; ++side) {
    const Polygon& own = *polys[side];
    const Polygon& other = *polys[1 - side];
    if (!consider(own.v[0], own.v[1], own.v[2])) {
      planeCount_ = 0;
      return;
    }
    for (int i = 0; i < own.count; ++i) {
      const Vec3 e0 = own.v[i], e1 = own.v[i + 1 == own.count ? 0 : i + 1];
      for (int k = 0; k < other.count; ++k)
        if (!consider(e0, e1, other.v[k])) {
          planeCount_ = 0;
          return;
        }
    }
  }
}

bool Shaft::mayIntersect(const Polygon& poly) const {
  if (planeCount_ == 0) return true;
  // Separated by a hull plane: every corner of the polygon outside it.
  for (int k = 0; k < planeCount_; ++k) {
    const glm::vec4& pl = planes_[size_t(k)];
    const Vec3 n(pl);
    bool outside = true;
    for (int i = 0; i < poly.count && outside; ++i) outside = glm::dot(n, poly.v[i]) + pl.w >= -tolerance_;
    if (outside) return false;
  }
  // Separated by the polygon's own plane: the whole hull on one side of it.
  const Vec3 n = poly.normal();
  const float w = -glm::dot(n, poly.v[0]);
  bool above = false, below = false;
  for (int i = 0; i < pointCount_; ++i) {
    float d = glm::dot(n, points_[size_t(i)]) + w;
    above |= d > tolerance_;
    below |= d < -tolerance_;
  }
  return above && below;
}

bool shaftIsClear(const Shaft& shaft, const RayTracer& faces, const std::function<Polygon(uint32_t)>& polygonOf,
                  uint32_t skipA, uint32_t skipB) {
  if (!shaft.valid()) return false;
  const Vec3 centre = 0.5f * (shaft.boundsMin() + shaft.boundsMax());
  const float radius = 0.5f * glm::length(shaft.boundsMax() - shaft.boundsMin());
  bool clear = true;
  int candidates = 0;
  faces.forEachNear(centre, radius, [&](uint32_t face) {
    if (face == skipA || face == skipB) return true;
    if (++candidates > kMaxShaftCandidates || shaft.mayIntersect(polygonOf(face))) clear = false;
    return clear;
  });
  return clear;
}

}  // namespace luxel
