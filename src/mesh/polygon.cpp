#include <algorithm>
#include <cmath>

#include "luxel/surface.h"

namespace luxel {

Vec3 Polygon::centroid() const {
  // Area-weighted centroid of the triangle fan, exact for any planar convex polygon.
  if (count == 3) return (v[0] + v[1] + v[2]) / 3.0f;
  float a0 = glm::length(glm::cross(v[1] - v[0], v[2] - v[0]));
  float a1 = glm::length(glm::cross(v[2] - v[0], v[3] - v[0]));
  Vec3 c0 = (v[0] + v[1] + v[2]) / 3.0f, c1 = (v[0] + v[2] + v[3]) / 3.0f;
  float total = a0 + a1;
  return total > 0.0f ? (c0 * a0 + c1 * a1) / total : (v[0] + v[1] + v[2] + v[3]) * 0.25f;
}

Vec3 Polygon::normal() const {
  // Newell's method: robust for slightly non-planar quads and well defined for triangles.
  Vec3 n(0.0f);
  for (int i = 0; i < count; ++i) {
    const Vec3& a = v[i];
    const Vec3& b = v[(i + 1) % count];
    n += Vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  float len = glm::length(n);
  return len > 0.0f ? n / len : Vec3(0.0f);
}

float Polygon::area() const {
  Vec3 sum(0.0f);
  for (int i = 1; i + 1 < count; ++i) sum += glm::cross(v[i] - v[0], v[i + 1] - v[0]);
  return 0.5f * glm::length(sum);
}

bool Polygon::hasArea() const {
  float longest = 0.0f;
  for (int i = 0; i < count; ++i) longest = std::max(longest, glm::length(v[(i + 1) % count] - v[i]));
  return area() > 1e-14f * longest * longest;
}

Vec3 SurfaceFace::position(Vec2 st) const {
  const float s = st.x, t = st.y;
  if (triangle) return corners[0] + s * (corners[1] - corners[0]) + t * (corners[2] - corners[0]);
  return (1 - s) * (1 - t) * corners[0] + s * (1 - t) * corners[1] + s * t * corners[2] +
         (1 - s) * t * corners[3];
}

Vec2 SurfaceFace::uv(Vec2 st) const {
  const float s = st.x, t = st.y;
  if (triangle) return uvs[0] + s * (uvs[1] - uvs[0]) + t * (uvs[2] - uvs[0]);
  return (1 - s) * (1 - t) * uvs[0] + s * (1 - t) * uvs[1] + s * t * uvs[2] + (1 - s) * t * uvs[3];
}

}  // namespace luxel
