#include "solve/emitter_direct.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/random.h"
#include "core/spherical_harmonics.h"
#include "luxel/error.h"
#include "transport/emitting_polygons.h"
#include "transport/form_factor.h"

namespace luxel {
namespace {

constexpr int kPoints = 4;      // 2 x 2 points of the element for the unoccluded factor
// 4 x 4 first rays, each from its own stratum of the element to its own stratum of the emitter:
// where a lamp is partly hidden (a share p of it seen) 16 rays all agree p^16 + (1 - p)^16 of the
// time, 0.3% at p = 0.3, where 4 did a quarter of the time and left the element wholly lit or
// dark (against path-traced probes: docs/performance.md, "Face-cluster radiosity").
constexpr int kFirstSide = 4;
constexpr int kMoreSide = 8;   // where the first rays disagree: 8 x 8 more

struct Ray {
  size_t pair;   // the (element, emitter) pair it tests
  float kernel;  // cos cos / r^2 at its ends
};

}  // namespace

size_t emittingPolygonCount(const SurfaceSet& surfaces) { return emittingPolygons(surfaces).size(); }

EmitterDirectLight emitterDirectLight(const SurfaceSet& surfaces, const RayTracer& tracer, int shCount, uint32_t seed) {
  EmitterDirectLight out;
  const size_t ne = surfaces.elements.size();
  out.irradiance.assign(ne, Rgb(0.0f));
  if (shCount > 0) out.sh.assign(ne * size_t(shCount), Rgb(0.0f));
  const std::vector<EmittingPolygon> emitters = emittingPolygons(surfaces);
  if (emitters.empty()) return out;
  if (emitters.size() > kMaxEmittingPolygons)
    throw Error(fmt::format("{} emitting polygons: per-element direct light visits at most {}", emitters.size(),
                            kMaxEmittingPolygons));
  const float offset = rayOffsetFor(surfaces.sceneExtent);
  std::atomic<uint64_t> traced{0};
  // Elements are taken in blocks whose rays go to Embree as one stream per pass: at seed 002's
  // 1.5M faces a stream per element spent more in the calls than in the rays.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, ne, 64), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<RTCRay> rays;
    std::vector<Ray> meta;
    struct Pair {
      uint32_t element, emitter;
      float factor;                   // unoccluded, the mean over the element's points
      float seen = 0.0f, all = 0.0f;  // kernel-weighted rays that arrive, and all
      int arrived = 0, cast = 0;
    };
    std::vector<Pair> pairs;
    std::vector<Rng> rngs;
    // A shadow ray for pair p from `from` to a point of its emitter in front of from's plane,
    // weighted by its kernel.
    auto cast = [&](size_t p, Vec3 from, float s, float t) {
      const Element& el = surfaces.elements[pairs[p].element];
      const EmittingPolygon& em = emitters[pairs[p].emitter];
      Rng& rng = rngs[pairs[p].element - range.begin()];
      Vec3 y;
      int drawn = 0;
      const auto next = [&] { return drawn < 2 ? (drawn++ == 0 ? s : t) : rng.next(); };
      if (!pointInFront(em.polygon, from, el.normal, next, y)) return;
      const Vec3 d = y - from;
      const float r2 = glm::dot(d, d);
      if (!(r2 > 0.0f)) return;
      const float kernel = glm::dot(el.normal, d) * -glm::dot(em.normal, d) / (r2 * r2);
      if (!(kernel > 0.0f)) return;
      const Vec3 xo = from + el.normal * offset, yo = y + em.normal * offset;
      rays.push_back(makeRay(xo, yo - xo, 0.0f, 1.0f));
      meta.push_back({p, kernel});
    };
    auto settle = [&] {
      tracer.occluded(rays);
      for (size_t r = 0; r < rays.size(); ++r) {
        Pair& pr = pairs[meta[r].pair];
        const bool arrives = !isOccluded(rays[r]);
        pr.all += meta[r].kernel, pr.cast += 1;
        if (arrives) pr.seen += meta[r].kernel, pr.arrived += 1;
      }
      traced.fetch_add(rays.size(), std::memory_order_relaxed);
      rays.clear(), meta.clear();
    };
    // Stratum i of a side x side grid over the element, jittered.
    auto stratum = [&](const Element& el, Rng& rng, int i, int side) {
      return polygonPoint(el.polygon, (float(i % side) + rng.next()) / float(side), (float(i / side) + rng.next()) / float(side));
    };
    for (size_t e = range.begin(); e < range.end(); ++e) {
      const Element& el = surfaces.elements[e];
      rngs.emplace_back(hashCombine(seed, uint32_t(e)));
      // The unoccluded factor by the 2 x 2 midpoint rule: jittered points were 2-8% off on the
      // smooth factor of a lamp a metre away (tests/unit/test_emitter_direct.cpp).
      Vec3 x[kPoints], n[kPoints];
      for (int i = 0; i < kPoints; ++i) {
        x[i] = polygonPoint(el.polygon, (float(i % 2) + 0.5f) * 0.5f, (float(i / 2) + 0.5f) * 0.5f);
        n[i] = el.normal;
      }
      for (uint32_t k = 0; k < emitters.size(); ++k) {
        const EmittingPolygon& em = emitters[k];
        float f[kPoints];
        pointToPolygonFormFactors4(x, n, em.polygon, em.normal, f);
        const float factor = 0.25f * (f[0] + f[1] + f[2] + f[3]);
        if (factor > 0.0f) pairs.push_back({uint32_t(e), k, factor});
      }
    }
    for (size_t p = 0; p < pairs.size(); ++p) {
      const Element& el = surfaces.elements[pairs[p].element];
      Rng& rng = rngs[pairs[p].element - range.begin()];
      for (int i = 0; i < kFirstSide * kFirstSide; ++i) {
        const Vec3 from = stratum(el, rng, i, kFirstSide);
        // The emitter's strata are the element's transposed, so that the rays cross.
        cast(p, from, (float(i / kFirstSide) + rng.next()) / float(kFirstSide),
             (float(i % kFirstSide) + rng.next()) / float(kFirstSide));
      }
    }
    settle();
    for (size_t p = 0; p < pairs.size(); ++p) {
      if (pairs[p].arrived == 0 || pairs[p].arrived == pairs[p].cast) continue;
      const Element& el = surfaces.elements[pairs[p].element];
      Rng& rng = rngs[pairs[p].element - range.begin()];
      for (int i = 0; i < kMoreSide * kMoreSide; ++i) cast(p, stratum(el, rng, i, kMoreSide), rng.next(), rng.next());
    }
    settle();
    for (const Pair& pr : pairs) {
      const size_t e = pr.element;
      const Element& el = surfaces.elements[e];
      const float visible = pr.all > 0.0f ? pr.seen / pr.all : 1.0f;
      const EmittingPolygon& em = emitters[pr.emitter];
      const Rgb part = em.exitance * (pr.factor * visible);
      out.irradiance[e] += part;
      if (shCount > 0 && visible > 0.0f) {
        // Band 0 from the emitter's solid angle and band 1 from its irradiance vector (the
        // integrals of L and of L w), at the centroid, as the hierarchy records its links.
        const PolygonMoments m = clippedPolygonMoments(el.centroid, el.normal, em.polygon, em.normal);
        constexpr float kPi = std::numbers::pi_v<float>;
        const Rgb radiance = em.exitance * (visible * std::max(m.solidAngle, kPi * glm::length(m.vector)) / kPi);
        Rgb* c = &out.sh[e * size_t(shCount)];
        c[0] += kShY0 * radiance;
        for (int ch = 0; ch < 3; ++ch) {
          const Vec3 v = m.vector * (visible * em.exitance[ch]);
          c[1][ch] += kShY1 * v.y, c[2][ch] += kShY1 * v.z, c[3][ch] += kShY1 * v.x;
        }
      }
    }
  });
  out.rays = traced.load();
  return out;
}

}  // namespace luxel
