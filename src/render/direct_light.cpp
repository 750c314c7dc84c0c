#include "render/direct_light.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "trace/element_polygons.h"
#include "trace/thin_glass.h"
#include "transport/emitting_polygons.h"
#include "transport/light_sampling.h"
#include "transport/shaft.h"

namespace luxel {
namespace {

// Up to this many emitters are all sampled at every point; beyond, kSampledEmitters are drawn by power.
constexpr size_t kMaxExplicitEmitters = 16;
constexpr int kSampledEmitters = 4;

// Each emitter's point is `u` shifted by an irrational step (a Cranley-Patterson rotation), so that
// the emitters of one sample do not all take the same corner of their strata.
Vec2 rotated(Vec2 u, size_t k) {
  const Vec2 step(0.61803399f, 0.41421356f);
  return glm::fract(u + float(k) * step);
}

// Above this many faces a shaft rarely comes out clear, and the faces' own BVH costs memory.
constexpr size_t kMaxShaftFaces = 65536;

enum : uint8_t { kUnknown = 0, kWhole = 1, kBlocked = 2 };

}  // namespace

struct DirectLight::Shafts {
  Shafts(const SurfaceSet& r, size_t emitters)
      : receivers(r),
        faces(facePolygons(r)),
        tracer(faces),
        tolerance(2.0f * rayOffsetFor(r.sceneExtent)),
        emitterCount(emitters),
        verdicts(std::make_unique<std::atomic<uint8_t>[]>(r.elements.size() * emitters)) {
    for (size_t i = 0; i < r.elements.size() * emitters; ++i) verdicts[i].store(kUnknown, std::memory_order_relaxed);
  }
  const SurfaceSet& receivers;
  std::vector<Polygon> faces;
  RayTracer tracer;  // over the faces, for a shaft's candidates
  float tolerance;   // faces touching a shaft's boundary (the walls a floor element meets) block nothing
  size_t emitterCount;
  std::unique_ptr<std::atomic<uint8_t>[]> verdicts;  // element * emitterCount + emitter
};

DirectLight::~DirectLight() = default;

bool DirectLight::seesWhole(uint32_t element, size_t k) const {
  std::atomic<uint8_t>& slot = shafts_->verdicts[size_t(element) * shafts_->emitterCount + k];
  const uint8_t known = slot.load(std::memory_order_relaxed);
  if (known != kUnknown) return known == kWhole;
  // Two threads may decide the same pair at once; both reach the same verdict.
  const Element& el = shafts_->receivers.elements[element];
  const int32_t twin = shafts_->receivers.faces[el.face].twin;
  const bool whole = shaftIsClear(Shaft(el.polygon, emitters_[k].polygon, shafts_->tolerance), shafts_->tracer,
                                  [&](uint32_t face) { return shafts_->faces[face]; }, el.face, uint32_t(twin));
  slot.store(whole ? kWhole : kBlocked, std::memory_order_relaxed);
  return whole;
}

DirectLight::DirectLight(const Scene& scene, const SurfaceSet& surfaces, const SurfaceSet* receivers, bool skies)
    : scene_(scene), skies_(skies), up_(glm::normalize(scene.up)) {
  for (const Light& l : scene.lights) lights_.push_back(prepareLight(l));
  for (const EmittingPolygon& p : emittingPolygons(surfaces))
    emitters_.push_back({p.polygon, p.normal, p.polygon.area(), p.exitance, Sides::Front});
  float total = 0.0f;
  for (const Emitter& em : emitters_) {
    total += em.polygon.area() * (em.exitance.r + em.exitance.g + em.exitance.b);
    cdf_.push_back(total);
  }
  for (float& c : cdf_) c /= total > 0.0f ? total : 1.0f;
  if (receivers && !emitters_.empty() && emitters_.size() <= kMaxExplicitEmitters &&
      receivers->faces.size() <= kMaxShaftFaces)
    shafts_ = std::make_unique<Shafts>(*receivers, emitters_.size());
}

Rgb DirectLight::sampleEmitter(const Emitter& em, float weight, Vec3 x, Vec3 n, Vec3 shading, Sides sides,
                               std::span<const Vec2> points, size_t rotation, Rng& rng, float rayOffset,
                               std::vector<RTCRay>& rays, std::vector<Rgb>& values, bool whole) const {
  const Vec3 pn = em.normal;
  // F and the area in front depend on x alone: once for all of x's light points.
  const float f = pointToPolygonFormFactor(x, shading, em.polygon, pn, sides, em.sides);
  if (f <= 0.0f) return Rgb(0.0f);
  const float count = float(points.size());
  if (whole) return em.exitance * (f * weight * count);  // V = 1 at every point: F exactly
  bool wholeInFront = true;
  for (int c = 0; c < em.polygon.count; ++c) wholeInFront &= glm::dot(em.polygon.v[size_t(c)] - x, shading) >= 0.0f;
  const float area = wholeInFront ? em.area : areaInFront(em.polygon, x, shading);
  Rgb always(0.0f);
  for (const Vec2 point : points) {
    // f counts only the part of the emitter above the shading plane; the point is drawn there. The
    // first try is the stratified point; a point behind the receiver's plane is drawn again.
    const Vec2 u = rotated(point, rotation);
    Vec3 y;
    int drawn = 0;
    const auto next = [&] { return drawn < 2 ? u[drawn++] : rng.next(); };
    if (!pointInFront(em.polygon, x, shading, next, y)) continue;  // a sliver
    const Vec3 d = y - x;
    const float r2 = glm::dot(d, d);
    if (!(r2 > 0.0f)) continue;
    const Vec3 w = d / std::sqrt(r2);
    const float cosReceiver =
        sides == Sides::Both ? std::abs(glm::dot(shading, w)) : std::max(0.0f, glm::dot(shading, w));
    const float cosEmitter = em.sides == Sides::Both ? std::abs(glm::dot(pn, w)) : std::max(0.0f, -glm::dot(pn, w));
    // What the shadow ray decides: this point's estimate of the factor, A k(y) (uniform points: the
    // bilinear map of polygonPoint is uniform on triangles and parallelograms, as emitters are).
    const float decided = area * cosReceiver * cosEmitter * std::numbers::inv_pi_v<float> / r2;
    always += em.exitance * ((f - decided) * weight);
    // A point below the geometric plane is hidden by the surface itself: blocked, without a ray.
    if (sides == Sides::Front && glm::dot(n, d) < 0.0f) continue;
    const Vec3 xo = x + n * (glm::dot(n, d) >= 0.0f ? rayOffset : -rayOffset);
    const Vec3 yo = y + pn * (glm::dot(pn, d) <= 0.0f ? rayOffset : -rayOffset);
    rays.push_back(makeRay(xo, yo - xo, 0.0f, 1.0f));
    // An emitting surface's light is blocked by glass, as in the solution, whose surfaces' light
    // does not pass it (trace/thin_glass.h).
    rays.back().id = kOpaqueToGlass;
    values.push_back(em.exitance * (decided * weight));
  }
  return always;
}

Rgb DirectLight::sample(Vec3 x, Vec3 n, Vec3 shading, Sides sides, std::span<const Vec2> points, Rng& rng,
                        float rayOffset, std::vector<RTCRay>& rays, std::vector<Rgb>& values, uint32_t element) const {
  Rgb always(0.0f);
  // A clear shaft proves the element sees the emitter whole; with a normal map's shading normal,
  // points above its plane may still lie behind the surface's own, so it is not used there.
  const bool shafts = shafts_ && element != kNoElement && shading == n && sides == Sides::Front;
  if (emitters_.size() <= kMaxExplicitEmitters) {
    for (size_t k = 0; k < emitters_.size(); ++k)
      always += sampleEmitter(emitters_[k], 1.0f, x, n, shading, sides, points, k, rng, rayOffset, rays, values,
                              shafts && seesWhole(element, k));
  } else {
    for (const Vec2& u : points)
      for (int i = 0; i < kSampledEmitters; ++i) {
        size_t k = size_t(std::lower_bound(cdf_.begin(), cdf_.end(), rng.next()) - cdf_.begin());
        k = std::min(k, emitters_.size() - 1);
        float p = cdf_[k] - (k > 0 ? cdf_[k - 1] : 0.0f);
        if (p <= 0.0f) continue;
        always += sampleEmitter(emitters_[k], 1.0f / (p * kSampledEmitters), x, n, shading, sides,
                                std::span<const Vec2>(&u, 1), size_t(i), rng, rayOffset, rays, values, false);
      }
  }
  for (const Vec2& u : points)
    for (size_t k = 0; k < scene_.lights.size(); ++k) {
      const Light& light = scene_.lights[k];
      if (!skies_ && isSkyLight(light)) continue;
      // The cosine at the shading normal; a direction behind the geometric plane is blocked by the
      // surface (never the case when shading == n: sampleLight gives those no light).
      const Vec2 ul = rotated(u, emitters_.size() + k);
      LightSample ls = sampleLight(lights_[k], x, shading, sides, up_, ul.x, ul.y);
      if (!ls.valid()) continue;
      if (sides == Sides::Front && glm::dot(n, ls.direction) < 0.0f) continue;
      Vec3 xo = x + n * (glm::dot(n, ls.direction) >= 0.0f ? rayOffset : -rayOffset);
      rays.push_back(makeRay(xo, ls.direction, 0.0f, ls.tfar));
      values.push_back(ls.irradiance);
    }
  return always;
}

}  // namespace luxel
