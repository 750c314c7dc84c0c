// Flat charts: orthogonal projection onto the plane of the chart's mean normal.
#include <cmath>

#include "lightmap/atlas_internal.h"

namespace luxel::lightmap {

bool planarProject(const WeldedMesh& w, Chart& chart) {
  Vec3 n = meanNormal(w, chart.faces);
  // Any orthonormal basis of the plane: the chart is rotated for packing later.
  Vec3 t = std::abs(n.x) < 0.9f ? glm::normalize(glm::cross(n, Vec3(1, 0, 0)))
                                : glm::normalize(glm::cross(n, Vec3(0, 1, 0)));
  Vec3 b = glm::cross(n, t);
  chart.uv.assign(chart.faces.size(), {});
  chart.planar = true;
  bool ok = true;
  for (size_t i = 0; i < chart.faces.size(); ++i) {
    uint32_t f = chart.faces[i];
    for (int k = 0; k < 4; ++k) {
      Vec3 p = w.positions[w.v[f][size_t(k)]];
      chart.uv[i][size_t(k)] = Vec2(glm::dot(p, t), glm::dot(p, b));
    }
    if (w.area[f] <= 0.0f) continue;
    const auto& uv = chart.uv[i];
    // A face that turns its back on the plane would fold over its neighbours.
    if (signedArea(uv[0], uv[1], uv[2]) <= 0.0f) ok = false;
    if (w.corners[f] == 4 && signedArea(uv[0], uv[2], uv[3]) <= 0.0f) ok = false;
  }
  return ok;
}

}  // namespace luxel::lightmap
