// A lightmap density from a texel budget: every texel is an element of the solve, so callers
// that default to the element budget get about as many texels as they would get elements.
#include <algorithm>
#include <cmath>

#include "luxel/lightmap.h"

namespace luxel {

double sceneFaceArea(const Scene& scene) {
  double area = 0.0;
  for (const Mesh& m : scene.meshes)
    for (const Face& f : m.faces) {
      const Vec3 p0 = m.positions[f.v[0]], p1 = m.positions[f.v[1]], p2 = m.positions[f.v[2]], p3 = m.positions[f.v[3]];
      area += 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
      if (!f.isTriangle()) area += 0.5 * glm::length(glm::cross(p2 - p0, p3 - p0));
    }
  return area;
}

float texelsPerMetreForBudget(const Scene& scene, size_t texels) {
  const double area = sceneFaceArea(scene);
  return area > 0.0 && texels > 0 ? float(std::sqrt(double(texels) / area)) : 0.0f;
}

float defaultTexelsPerMetre(const Scene& scene) {
  return std::max(kGameTexelsPerMetre, texelsPerMetreForBudget(scene, kSmallSceneTexels));
}

}  // namespace luxel
