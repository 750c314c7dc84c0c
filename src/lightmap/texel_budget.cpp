// A lightmap density from a texel budget: every texel is an element of the solve, so callers
// that default to the element budget get about as many texels as they would get elements.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

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
  const float wanted = std::max(kGameTexelsPerMetre, texelsPerMetreForBudget(scene, kSmallSceneTexels));
  const float most = texelsPerMetreForBudget(scene, size_t(kDefaultMaxTexels));
  return most > 0.0f ? std::min(wanted, most) : wanted;
}

std::string defaultDensityWarning(const Scene& scene) {
  const float density = defaultTexelsPerMetre(scene);
  if (!(density < kGameTexelsPerMetre)) return {};
  const double area = sceneFaceArea(scene);
  return fmt::format("scene '{}': its faces cover {:.3g} m2, where {:g} texels per metre would make {:.3g} lightmap "
                     "texels; the default is {:.3g} texels per metre ({:.3g} texels). If the file is not in metres, "
                     "scale it in a scene JSON (\"scale\", docs/scene-format.md); or give --texels-per-metre",
                     scene.name, area, kGameTexelsPerMetre, area * kGameTexelsPerMetre * kGameTexelsPerMetre, density,
                     kDefaultMaxTexels);
}

}  // namespace luxel
