#include "mesh/surface_hash.h"

namespace luxel {

void hashSurfaces(ContentHash& h, const SurfaceSet& surfaces) {
  h.value(uint64_t(surfaces.elements.size()));
  for (const Element& e : surfaces.elements) {
    h.value(e.polygon.count);
    h.bytes(e.polygon.v.data(), sizeof(Vec3) * size_t(e.polygon.count));
    h.bytes(e.param.data(), sizeof(e.param));
    h.value(e.face), h.value(e.centroid), h.value(e.normal), h.value(e.area), h.value(e.reflectance), h.value(e.exitance);
  }
  h.value(uint64_t(surfaces.faces.size()));
  for (const SurfaceFace& f : surfaces.faces) h.value(f.corners), h.value(f.triangle);
}

}  // namespace luxel
