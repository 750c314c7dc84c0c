// How SurfaceSet::splitElement cuts an element into four, as corner coordinates: quads at their
// parameter midpoints, triangles at their edge midpoints. The cut is linear in the coordinates, so
// the same function gives the children's corners in the face's parameters (splitElement) and in
// their parent's own interpolation coordinates (render/gather_mesh.h).
#pragma once

#include <array>
#include <glm/glm.hpp>

namespace luxel {

using Vec2 = glm::vec2;

// The four children's corners of an element with corners `p`. A triangle's corners are p[0..2];
// each child triangle repeats its third corner as its fourth, as elements do.
inline std::array<std::array<Vec2, 4>, 4> splitCorners(const std::array<Vec2, 4>& p,
                                                       bool triangle) {
  if (triangle) {
    const Vec2 ab = 0.5f * (p[0] + p[1]), bc = 0.5f * (p[1] + p[2]), ca = 0.5f * (p[2] + p[0]);
    return {{{p[0], ab, ca, ca}, {ab, p[1], bc, bc}, {ca, bc, p[2], p[2]}, {ab, bc, ca, ca}}};
  }
  const Vec2 m01 = 0.5f * (p[0] + p[1]), m12 = 0.5f * (p[1] + p[2]), m23 = 0.5f * (p[2] + p[3]),
             m30 = 0.5f * (p[3] + p[0]), mid = 0.25f * (p[0] + p[1] + p[2] + p[3]);
  return {
      {{p[0], m01, mid, m30}, {m01, p[1], m12, mid}, {mid, m12, p[2], m23}, {m30, mid, m23, p[3]}}};
}

}  // namespace luxel
