// Path-traced element irradiance: see transport/path_traced_irradiance.h.
#include "transport/path_traced_irradiance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "core/random.h"
#include "luxel/error.h"
#include "render/direct_light.h"
#include "trace/hemisphere_rays.h"
#include "trace/ray_tracer.h"
#include "transport/form_factor.h"

namespace luxel {
namespace {

// Paths traced together as one wavefront: one Embree stream per bounce.
constexpr uint32_t kBatch = 1024;
// A path of 1,000 bounces has carried less than 1e-4 of its light for any reflectance up to 0.99;
// the cap only stops a closed scene of reflectance 1, whose irradiance is infinite.
constexpr int kMaxBounces = 1000;

float largest(Rgb c) { return std::max(c.r, std::max(c.g, c.b)); }

struct Scratch {
  std::vector<Rgb> values;  // per path of the batch: the irradiance it estimates
  std::vector<Rng> rngs;
  std::vector<Rgb> throughput;
  std::vector<uint32_t> pathOf;  // per live ray
  std::vector<RTCRayHit> rays;
  std::vector<RTCRay> shadowRays;
  std::vector<Rgb> shadowValues;
  std::vector<uint32_t> shadowPath;
};

class Tracer {
 public:
  Tracer(const SurfaceSet& surfaces, const RayTracer& rays, const DirectLight& direct, int maxBounces)
      : surfaces_(surfaces),
        rays_(rays),
        direct_(direct),
        offset_(rayOffsetFor(surfaces.sceneExtent)),
        maxBounces_(std::min(maxBounces, kMaxBounces)) {}

  ElementIrradianceEstimate estimate(uint32_t element, const PathTracingOptions& o, Scratch& s) const {
    const Element& e = surfaces_.elements[element];
    const uint32_t elementSeed = hashCombine(o.seed, element);
    double sum[3] = {0, 0, 0}, sumSq[3] = {0, 0, 0};
    uint32_t paths = 0;
    ElementIrradianceEstimate out;
    while (paths < o.maxPaths) {
      const uint32_t batch = std::min(kBatch, o.maxPaths - paths);
      traceBatch(e, elementSeed, paths, batch, s);
      for (uint32_t p = 0; p < batch; ++p)
        for (int c = 0; c < 3; ++c) {
          const double v = s.values[p][c];
          sum[c] += v, sumSq[c] += v * v;
        }
      paths += batch;
      double mean = 0.0, variance = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double m = sum[c] / paths;
        mean += m;
        variance += std::max(0.0, sumSq[c] / paths - m * m) / std::max(1.0, double(paths) - 1.0);
      }
      // The channels' errors are summed as if independent; they are correlated (the same paths),
      // which this underestimates by at most sqrt(3), and only for coloured light.
      if (paths >= o.minPaths && std::sqrt(variance) <= o.relativeError * mean) break;
      if (paths >= o.minPaths && mean <= 0.0) break;  // no light reaches it: every path returned 0
    }
    out.paths = paths;
    for (int c = 0; c < 3; ++c) {
      const double m = sum[c] / paths;
      out.mean[c] = float(m);
      out.standardError[c] = float(std::sqrt(std::max(0.0, sumSq[c] / paths - m * m) / std::max(1.0, paths - 1.0)));
    }
    return out;
  }

 private:
  // Paths [first, first + count) of the element: each starts at a uniform point on it, takes the
  // direct light there, and follows cosine-distributed bounces, each hit adding its own direct
  // light weighted by the reflectances on the way (the pi of the cosine pdf cancels the 1/pi of
  // the Lambertian BRDF). Emission met by a bounce is not counted: next-event estimation already
  // took it.
  void traceBatch(const Element& e, uint32_t elementSeed, uint32_t first, uint32_t count, Scratch& s) const {
    s.values.assign(count, Rgb(0.0f));
    s.rngs.clear(), s.throughput.assign(count, Rgb(1.0f));
    s.rays.clear(), s.pathOf.clear();
    s.shadowRays.clear(), s.shadowValues.clear(), s.shadowPath.clear();
    const HemisphereFrame frame(e.normal);
    for (uint32_t p = 0; p < count; ++p) {
      Rng& rng = s.rngs.emplace_back(hashCombine(elementSeed, first + p));
      const float pick = rng.next(), a = rng.next(), b = rng.next();
      const Vec3 x = uniformPolygonPoint(e.polygon, pick, a, b);
      addDirect(p, x, e.normal, Rgb(1.0f), rng, s);
      if (maxBounces_ == 0) continue;
      const float u1 = rng.next(), u2 = rng.next();
      s.rays.emplace_back().ray = makeRay(x + offset_ * e.normal, frame.cosine(u1, u2), 0.0f,
                                          std::numeric_limits<float>::infinity());
      s.pathOf.push_back(p);
    }
    for (int bounce = 0; bounce < maxBounces_ && !s.rays.empty(); ++bounce) {
      rays_.intersect(s.rays, false);
      size_t live = 0;
      for (size_t k = 0; k < s.rays.size(); ++k) {
        const RTCRayHit rh = s.rays[k];
        const uint32_t p = s.pathOf[k];
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        const Element& hit = surfaces_.elements[rh.hit.primID];
        const Vec3 d(rh.ray.dir_x, rh.ray.dir_y, rh.ray.dir_z);
        if (glm::dot(hit.normal, d) >= 0.0f) continue;  // a back: absorbed, as the solvers absorb it
        Rgb& t = s.throughput[p];
        t *= hit.reflectance;
        const float survive = std::min(1.0f, largest(t));
        if (!(survive > 0.0f)) continue;
        Rng& rng = s.rngs[p];
        const Vec3 q = Vec3(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z) + d * rh.ray.tfar;
        addDirect(p, q, hit.normal, t, rng, s);
        if (bounce + 1 >= maxBounces_ || rng.next() >= survive) continue;  // Russian roulette
        t /= survive;
        const float u1 = rng.next(), u2 = rng.next();
        s.rays[live].ray = makeRay(q + offset_ * hit.normal, HemisphereFrame(hit.normal).cosine(u1, u2), 0.0f,
                                   std::numeric_limits<float>::infinity());
        s.rays[live].hit.geomID = RTC_INVALID_GEOMETRY_ID;
        s.pathOf[live++] = p;
      }
      s.rays.resize(live), s.pathOf.resize(live);
      traceShadows(s);
    }
    traceShadows(s);
  }

  void addDirect(uint32_t p, Vec3 x, Vec3 n, Rgb weight, Rng& rng, Scratch& s) const {
    const size_t before = s.shadowRays.size();
    s.values[p] += weight * direct_.sample(x, n, Sides::Front, rng, offset_, s.shadowRays, s.shadowValues);
    for (size_t r = before; r < s.shadowRays.size(); ++r) {
      s.shadowValues[r] *= weight;
      s.shadowPath.push_back(p);
    }
  }

  void traceShadows(Scratch& s) const {
    if (s.shadowRays.empty()) return;
    rays_.occluded(s.shadowRays);
    for (size_t r = 0; r < s.shadowRays.size(); ++r)
      if (!isOccluded(s.shadowRays[r])) s.values[s.shadowPath[r]] += s.shadowValues[r];
    s.shadowRays.clear(), s.shadowValues.clear(), s.shadowPath.clear();
  }

  const SurfaceSet& surfaces_;
  const RayTracer& rays_;
  const DirectLight& direct_;
  float offset_;
  int maxBounces_;
};

}  // namespace

std::vector<ElementIrradianceEstimate> pathTraceElementIrradiance(const Scene& scene, const SurfaceSet& surfaces,
                                                                  std::span<const uint32_t> elements,
                                                                  const PathTracingOptions& options,
                                                                  const ProgressCallback& progress) {
  for (const SurfaceFace& f : surfaces.faces)
    if (f.twin >= 0)
      throw Error("path-traced irradiance: two-sided faces (material twoSided) are not supported: their two sides "
                  "coincide and a ray cannot tell which one it met");
  for (uint32_t e : elements)
    if (e >= surfaces.elements.size())
      throw Error(fmt::format("path-traced irradiance: element {} of {} does not exist", e, surfaces.elements.size()));
  if (options.minPaths < 2 || options.maxPaths < options.minPaths || !(options.relativeError >= 0.0) ||
      options.maxBounces < 0)
    throw Error(fmt::format("path-traced irradiance: paths {}..{} at relative error {} and {} bounces make no estimate",
                            options.minPaths, options.maxPaths, options.relativeError, options.maxBounces));
  std::vector<Polygon> polygons;
  polygons.reserve(surfaces.elements.size());
  for (const Element& e : surfaces.elements) polygons.push_back(e.polygon);
  const RayTracer rays(polygons);
  const DirectLight direct(scene, surfaces);
  const Tracer tracer(surfaces, rays, direct, options.maxBounces);

  std::vector<ElementIrradianceEstimate> out(elements.size());
  // Elements are handed out in rounds so that progress (and cancelling) runs on this thread.
  const size_t round = 64;
  for (size_t begin = 0; begin < elements.size(); begin += round) {
    reportProgress(progress, "path tracing", double(begin) / double(elements.size()),
                   fmt::format("{} of {} elements", begin, elements.size()));
    const size_t end = std::min(elements.size(), begin + round);
    tbb::parallel_for(begin, end, [&](size_t i) {
      thread_local Scratch scratch;
      out[i] = tracer.estimate(elements[i], options, scratch);
    });
  }
  reportProgress(progress, "path tracing", 1.0, fmt::format("{} elements", elements.size()));
  return out;
}

}  // namespace luxel
