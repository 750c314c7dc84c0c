#include "transport/emitting_polygons.h"

namespace luxel {

std::vector<EmittingPolygon> emittingPolygons(const SurfaceSet& surfaces) {
  // A face is uniform when every element of it carries its first element's exitance.
  std::vector<int8_t> uniform(surfaces.faces.size(), -1);
  std::vector<Rgb> first(surfaces.faces.size(), Rgb(0.0f));
  for (const Element& e : surfaces.elements) {
    int8_t& u = uniform[e.face];
    if (u < 0) u = 1, first[e.face] = e.exitance;
    else if (first[e.face] != e.exitance) u = 0;
  }
  std::vector<EmittingPolygon> out;
  std::vector<bool> faceDone(surfaces.faces.size(), false);
  for (const Element& e : surfaces.elements) {
    if (!(e.exitance.r > 0.0f || e.exitance.g > 0.0f || e.exitance.b > 0.0f)) continue;
    if (uniform[e.face] == 1) {
      if (faceDone[e.face]) continue;
      faceDone[e.face] = true;
      const SurfaceFace& f = surfaces.faces[e.face];
      const Polygon polygon{f.corners, f.triangle ? 3 : 4};
      out.push_back({polygon, polygon.normal(), e.exitance});
    } else {
      out.push_back({e.polygon, e.polygon.normal(), e.exitance});
    }
  }
  return out;
}

}  // namespace luxel
