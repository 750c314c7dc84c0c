#include "trace/convex_solid.h"

#include <algorithm>
#include <cmath>

namespace luxel {

ConvexSolid ConvexSolid::fromPolygons(std::span<const Polygon> polygons, float tolerance) {
  ConvexSolid solid;
  std::vector<glm::vec4> planes;
  Vec3 areaVector(0.0f);
  double totalArea = 0.0;
  for (const Polygon& p : polygons) {
    if (!p.hasArea()) continue;
    const Vec3 n = p.normal();
    const float d = glm::dot(n, p.centroid());
    areaVector += n * p.area();
    totalArea += double(p.area());
    bool known = false;
    for (const glm::vec4& q : planes)
      known |= glm::dot(Vec3(q), n) > 1.0f - 1e-5f && std::abs(q.w - d) <= tolerance;
    if (known) continue;
    if (planes.size() == kMaxPlanes) return solid;
    planes.emplace_back(n, d);
  }
  // Closed: the outward area vectors of a closed surface sum to zero. An open box (a missing
  // face) or a lone plane leaves the sum of the missing part.
  if (planes.size() < 4 || !(double(glm::length(areaVector)) <= 1e-4 * totalArea)) return solid;
  // Convex, and the normals outward: every corner lies behind every face's plane. A room's inward
  // walls fail here.
  for (const Polygon& p : polygons)
    for (int i = 0; i < p.count; ++i)
      for (const glm::vec4& q : planes)
        if (glm::dot(Vec3(q), p.v[size_t(i)]) > q.w + tolerance) return solid;
  solid.planes_ = std::move(planes);
  return solid;
}

bool ConvexSolid::segmentMeets(Vec3 a, Vec3 b, float inset) const {
  // Cyrus and Beck: clip the segment's parameter interval by each half-space.
  const Vec3 d = b - a;
  float t0 = 0.0f, t1 = 1.0f;
  for (const glm::vec4& q : planes_) {
    const Vec3 n(q);
    const float start = glm::dot(n, a) - (q.w - inset), rate = glm::dot(n, d);
    if (rate == 0.0f) {
      if (start > 0.0f) return false;
      continue;
    }
    const float t = -start / rate;
    if (rate > 0.0f)
      t1 = std::min(t1, t);
    else
      t0 = std::max(t0, t);
    if (t0 > t1) return false;
  }
  return true;
}

ConvexSolid::Segment ConvexSolid::classify(Vec3 a, Vec3 b, float margin) const {
  // Cyrus and Beck twice over, for the solid grown and shrunk by the margin.
  const Vec3 d = b - a;
  float grownIn = 0.0f, grownOut = 1.0f, shrunkIn = 0.0f, shrunkOut = 1.0f;
  bool endOutside = false;
  for (const glm::vec4& q : planes_) {
    const Vec3 n(q);
    const float start = glm::dot(n, a) - q.w, rate = glm::dot(n, d);
    endOutside |= start > margin || start + rate > margin;
    if (rate == 0.0f) {
      if (start > margin) return Segment::Clear;
      if (start > -margin) shrunkOut = -1.0f;  // parallel, outside the shrunk solid
      continue;
    }
    const float tGrown = -(start - margin) / rate, tShrunk = -(start + margin) / rate;
    if (rate > 0.0f)
      grownOut = std::min(grownOut, tGrown), shrunkOut = std::min(shrunkOut, tShrunk);
    else
      grownIn = std::max(grownIn, tGrown), shrunkIn = std::max(shrunkIn, tShrunk);
    if (grownIn > grownOut) return Segment::Clear;
  }
  return shrunkIn <= shrunkOut && endOutside ? Segment::Crosses : Segment::Unsure;
}

bool ConvexSolid::blocksEverySegment(const Polygon& a, const Polygon& b, float inset) const {
  if (!valid()) return false;
  for (int i = 0; i < a.count; ++i)
    for (int j = 0; j < b.count; ++j)
      if (!segmentMeets(a.v[size_t(i)], b.v[size_t(j)], inset)) return false;
  return true;
}

bool ConvexSolid::separatedFrom(const Polygon& p, float gap) const {
  for (const glm::vec4& q : planes_) {
    bool outside = true;
    for (int i = 0; i < p.count && outside; ++i) outside = glm::dot(Vec3(q), p.v[size_t(i)]) > q.w + gap;
    if (outside) return true;
  }
  return false;
}

}  // namespace luxel
