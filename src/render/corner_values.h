// Nodal averaging with the corner groups given, for callers that average several fields over the
// same surfaces (the viewer: three fields each time the solution changes) and build the groups once.
#pragma once

#include <array>
#include <vector>

#include "luxel/surface.h"
#include "mesh/corner_groups.h"

namespace luxel {

// A corner field at a hit's parameters (RayTracer::intersect's u, v): barycentric on triangles,
// bilinear on quads.
template <typename T>
T interpolateCorners(const T* c, int count, float u, float v) {
  if (count == 3) return (1.0f - u - v) * c[0] + u * c[1] + v * c[2];
  return (1.0f - u) * (1.0f - v) * c[0] + u * (1.0f - v) * c[1] + u * v * c[2] + (1.0f - u) * v * c[3];
}

// The weight interpolateCorners gives each corner at (u, v); 0 past `count`.
inline std::array<float, 4> cornerWeights(int count, float u, float v) {
  if (count == 3) return {1.0f - u - v, u, v, 0.0f};
  return {(1.0f - u) * (1.0f - v), u * (1.0f - v), u * v, (1.0f - u) * v};
}

// The normal of the smooth surface at corner c of element e: the area-weighted mean of the normals
// of the elements its corner group joins (`groups` built from `surfaces`), the element's own where
// they cancel. What a highlight follows on a curved mesh, whose facets the light does not show.
inline Vec3 smoothCornerNormal(const SurfaceSet& surfaces, const CornerGroups& groups, uint32_t e, int c) {
  Vec3 smooth(0.0f);
  for (uint32_t m : groups.at(e, c)) smooth += surfaces.elements[m].area * surfaces.elements[m].normal;
  return glm::length(smooth) > 0.0f ? glm::normalize(smooth) : surfaces.elements[e].normal;
}

// elementCornerValues (luxel/render.h) over `groups`, built from the same surfaces.
std::vector<Rgb> elementCornerValues(const SurfaceSet& surfaces, const CornerGroups& groups, const std::vector<Rgb>& perElement);

}  // namespace luxel
