// Texel-centre rasterisation with a top-left rule, for the overlap checks.
#include <algorithm>
#include <cmath>

#include "lightmap/atlas_internal.h"

namespace luxel::lightmap {

void rasteriseTriangle(Vec2 a, Vec2 b, Vec2 c, int size, const std::function<void(int, int)>& f) {
  glm::dvec2 p[3] = {a, b, c};
  double area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
  if (!(area != 0.0) || !std::isfinite(area)) return;
  if (area < 0.0) std::swap(p[1], p[2]);  // counter-clockwise from here on
  double x0 = std::min({p[0].x, p[1].x, p[2].x}), x1 = std::max({p[0].x, p[1].x, p[2].x});
  double y0 = std::min({p[0].y, p[1].y, p[2].y}), y1 = std::max({p[0].y, p[1].y, p[2].y});
  int ix0 = std::max(0, int(std::ceil(x0 - 0.5))), ix1 = std::min(size - 1, int(std::floor(x1 - 0.5)));
  int iy0 = std::max(0, int(std::ceil(y0 - 0.5))), iy1 = std::min(size - 1, int(std::floor(y1 - 0.5)));
  // An edge owns the centres on it when it runs downwards, or leftwards when horizontal: of two
  // triangles sharing an edge (run in opposite directions), exactly one owns it.
  bool owns[3];
  for (int e = 0; e < 3; ++e) {
    glm::dvec2 d = p[(e + 1) % 3] - p[e];
    owns[e] = d.y < 0.0 || (d.y == 0.0 && d.x < 0.0);
  }
  for (int y = iy0; y <= iy1; ++y)
    for (int x = ix0; x <= ix1; ++x) {
      glm::dvec2 q(x + 0.5, y + 0.5);
      bool inside = true;
      for (int e = 0; e < 3 && inside; ++e) {
        glm::dvec2 s = p[e], d = p[(e + 1) % 3] - s;
        double side = d.x * (q.y - s.y) - d.y * (q.x - s.x);
        inside = side > 0.0 || (side == 0.0 && owns[e]);
      }
      if (inside) f(x, y);
    }
}

}  // namespace luxel::lightmap
