// Quad recovery after triangulation (see quads.h).
#include "scene/import/quads.h"

#include <cmath>

namespace luxel {
namespace {

// Sine of the smallest turn accepted at a quad corner: three nearly collinear corners make a
// sliver, not a quad.
constexpr float kMinCornerSine = 1e-4f;

bool unitNormal(Vec3 a, Vec3 b, Vec3 c, Vec3& n) {
  Vec3 cr = glm::cross(b - a, c - a);
  float len = glm::length(cr);
  if (!(len > 0.0f) || !std::isfinite(len)) return false;
  n = cr / len;
  return true;
}

// Each corner of a convex quad turns the same way as the quad's normal.
bool convexCorner(Vec3 prev, Vec3 at, Vec3 next, Vec3 n) {
  Vec3 e0 = at - prev;
  Vec3 e1 = next - at;
  float scale = glm::length(e0) * glm::length(e1);
  return scale > 0.0f && glm::dot(glm::cross(e0, e1), n) > kMinCornerSine * scale;
}

bool mergeable(const std::vector<Vec3>& p, const std::array<uint32_t, 3>& t0,
               const std::array<uint32_t, 3>& t1) {
  // The pattern (a,b,c), (a,c,d) with four distinct vertices.
  if (t0[0] != t1[0] || t0[2] != t1[1]) return false;
  uint32_t a = t0[0], b = t0[1], c = t0[2], d = t1[2];
  if (a == b || a == c || a == d || b == c || b == d || c == d) return false;
  Vec3 n0, n1;
  if (!unitNormal(p[a], p[b], p[c], n0) || !unitNormal(p[a], p[c], p[d], n1)) return false;
  if (glm::length(n0 - n1) > kQuadNormalTolerance) return false;
  Vec3 n = glm::normalize(n0 + n1);
  return convexCorner(p[d], p[a], p[b], n) && convexCorner(p[a], p[b], p[c], n) &&
         convexCorner(p[b], p[c], p[d], n) && convexCorner(p[c], p[d], p[a], n);
}

}  // namespace

std::vector<Face> recoverQuads(const std::vector<Vec3>& positions,
                               const std::vector<std::array<uint32_t, 3>>& triangles) {
  std::vector<Face> faces;
  faces.reserve(triangles.size());
  size_t i = 0;
  while (i < triangles.size()) {
    const auto& t0 = triangles[i];
    if (i + 1 < triangles.size() && mergeable(positions, t0, triangles[i + 1])) {
      faces.push_back(Face{{t0[0], t0[1], t0[2], triangles[i + 1][2]}});
      i += 2;
    } else {
      faces.push_back(Face{{t0[0], t0[1], t0[2], t0[2]}});
      i += 1;
    }
  }
  return faces;
}

}  // namespace luxel
