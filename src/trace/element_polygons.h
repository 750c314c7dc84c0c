// The surfaces as polygons for ray tracers: the faces whole, or the elements with the two sides of a
// two-sided face apart.
#pragma once

#include <vector>

#include "luxel/surface.h"
#include "trace/ray_tracer.h"

namespace luxel {

// Every face as a polygon, in SurfaceSet::faces' order.
inline std::vector<Polygon> facePolygons(const SurfaceSet& surfaces) {
  std::vector<Polygon> polygons(surfaces.faces.size());
  for (size_t i = 0; i < polygons.size(); ++i)
    polygons[i] = Polygon{surfaces.faces[i].corners, surfaces.faces[i].triangle ? 3 : 4};
  return polygons;
}

// Coplanar twins (the two sides of a two-sided face) would be hit at random. Each is nudged half a
// ray offset (rayOffsetFor) along its own normal, so that a ray from either side meets the side
// that faces it first; rays leave a surface a whole offset out, past both of its twins.
inline std::vector<Polygon> elementPolygonsTwinsApart(const SurfaceSet& surfaces) {
  const float offset = rayOffsetFor(surfaces.sceneExtent);
  std::vector<Polygon> polygons(surfaces.elements.size());
  for (size_t e = 0; e < polygons.size(); ++e) {
    const Element& el = surfaces.elements[e];
    polygons[e] = el.polygon;
    if (surfaces.faces[el.face].twin >= 0)
      for (int k = 0; k < polygons[e].count; ++k) polygons[e].v[size_t(k)] += 0.5f * offset * el.normal;
  }
  return polygons;
}

}  // namespace luxel
