// A final gather of incident radiance in SH: see solve/gathered_sh.h.
#include "solve/gathered_sh.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/spherical_harmonics.h"
#include "trace/element_polygons.h"
#include "trace/hemisphere_rays.h"
#include "trace/ray_tracer.h"

namespace luxel {

std::vector<Rgb> gatherIncidentSh(const SurfaceSet& surfaces, const std::vector<Rgb>& radiosity, int count, int rays) {
  const size_t ne = surfaces.elements.size();
  std::vector<Rgb> out(ne * size_t(count), Rgb(0.0f));
  const float offset = rayOffsetFor(surfaces.sceneExtent);
  const std::vector<Polygon> polygons = elementPolygonsTwinsApart(surfaces);
  RayTracer tracer(polygons);
  const int side = strataSide(rays);
  const float perRay = 2.0f * std::numbers::pi_v<float> / float(side * side);  // uniform: 2 pi / N
  tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 16), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<RTCRayHit> hits(size_t(side * side));
    std::vector<Vec3> dirs(hits.size());
    for (size_t ei = r.begin(); ei < r.end(); ++ei) {
      const Element& e = surfaces.elements[ei];
      const Vec3 n = e.normal;
      HemisphereStrata(n, side, ei, 4099u).directions(HemisphereStrata::Warp::Uniform, dirs);
      for (size_t k = 0; k < hits.size(); ++k)
        hits[k].ray = makeRay(e.centroid + offset * n, dirs[k], 0.0f, std::numeric_limits<float>::infinity());
      tracer.intersect(hits, false);
      Rgb* c = out.data() + ei * size_t(count);
      for (const RTCRayHit& rh : hits) {
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        const uint32_t hit = rh.hit.primID;
        const Vec3 d(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
        if (glm::dot(surfaces.elements[hit].normal, d) >= 0.0f) continue;  // its back: black
        shAddDirection(c, count, glm::normalize(d), (perRay / std::numbers::pi_v<float>) * radiosity[hit]);
      }
    }
  });
  return out;
}

}  // namespace luxel
